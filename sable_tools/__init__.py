"""sable's Python side: the reference harness (running sable, LIGGGHTS and YADE on a deck),
one reader per output format, the statistics over seeds, and the studies' scripts.

Run a script as a module from the repository root, e.g. `python3 -m sable_tools.compare DECK`.
"""
