"""One reader per output format: screen (sable's and LIGGGHTS' screen and log text), dump (text
dumps), ave_time (fix ave/time text files), h5 (sable's HDF5), yade (the YADE recorders' states
files), analyze (sable-analyze's CSV)."""
