"""The tutorial runner's speed table (sable_tools/tutorials/run.py --speed)."""


def test_speed_table_gives_cpu_times_and_their_ratio():
    from sable_tools.tutorials.run import speed_table
    recs = [{'tutorial': 'conveyor', 'code': 'sable', 'ok': True, 'cpu_s': 2.0},
            {'tutorial': 'conveyor', 'code': 'liggghts', 'ok': True, 'cpu_s': 5.0},
            {'tutorial': 'meshGran', 'code': 'sable', 'ok': False, 'cpu_s': 1.0},  # a failed run has no time
            {'tutorial': 'meshGran', 'code': 'liggghts', 'ok': True, 'cpu_s': 3.0}]
    rows = speed_table(recs, ['sable', 'liggghts'])
    assert '| conveyor | 1 | 2.00 | 5.00 | 2.50 |' in rows
    assert '| meshGran | 1 | n/a | 3.00 | n/a |' in rows
    assert rows[-1].startswith('median liggghts / sable: 2.50 over 1 tutorials')
