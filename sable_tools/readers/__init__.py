"""One reader per output format: screen (sable's and LIGGGHTS' screen and log text: OBSERVABLE
lines, thermo tables, KEY k=v lines, timing blocks, ERROR lines), dump (text dumps: dump custom's
last snapshot, dump local's rows), ave_time (fix ave/time text files), h5 (sable's HDF5: fix
ave/time series, fix ave/cg fields), vtk (VTK files: legacy text or binary, XML ascii or binary), yade (the YADE recorders' states
files), analyze (sable-analyze's CSV and HDF5)."""
