"""The ``topostore`` command line: the group in :mod:`.group`, one module per command family.

The outermost layer: it starts the server, the demo and the ROS node, so it may import all of them.
"""
