"""Pure physics functions: arrays in, arrays out, SI units, no I/O."""
