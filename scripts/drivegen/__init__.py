"""A second generator of synthetic drives, written apart from `ramap synthesize`.

What is tuned on one generator is checked on the other: this one has its own landmark placement
(facades in blocks at random setbacks, side streets, tunnels, poles, far points; rooms for the
hand-held and MAV motions), its own visibility and track lengths, its own timing (stops inserted
into the trajectory), its own pair selection and its own ways of being wrong (aliased pairs in
bursts, at every frame gap and angle, translation-only aliasing, outlier matches). It writes a
COLMAP 3.8 database with numpy and sqlite3 only, so that it shares no code with ramap.
"""
