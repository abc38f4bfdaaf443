"""Line dynamics about the static shape: the discretised line model (:mod:`.model`),
prescribed end motion (:mod:`.excitation`), implicit time integration
(:mod:`.integrator`), the steady periodic response (:mod:`.timedomain`), and modal
analysis (:mod:`.modal`) with Irvine's linear theory of shallow cables as its reference
(:mod:`.irvine`)."""
