"""Line dynamics: the discretised line model (:mod:`.model`), prescribed end motion
(:mod:`.excitation`), implicit time integration (:mod:`.integrator`) and the steady
periodic response (:mod:`.timedomain`)."""
