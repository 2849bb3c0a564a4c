"""One reader per output format: screen (sable and LIGGGHTS screen and log text), dump (text
dumps), ave_time (fix ave/time files), yade (the YADE recorders' states files), h5 (sable's HDF5)."""
