"""Small decks shared by the Python tests."""


def falling_pair(thermo, between="", after=""):
    """Two grains falling under gravity: runs of 50 and 30 steps, a thermo row every 10
    steps; `thermo` the thermo_style custom columns (v_z1 is the first grain's height),
    `between` and `after` deck lines between the runs and at the end."""
    return f"""units si
atom_style granular
region box block 0 1 0 1 0 1 units box
create_box 1 box
create_atoms 1 single 0.5 0.5 0.5 units box
create_atoms 1 single 0.2 0.5 0.5 units box
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere
variable z1 equal z[1]
thermo_style custom {thermo}
thermo 10
run 50
{between}
run 30
{after}
"""
