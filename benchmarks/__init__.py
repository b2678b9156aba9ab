"""Reasoning-latency benchmarks: ``python -m benchmarks [--quick] [--skip-100k]`` (``make bench``).

One robot step — REPLACE isIn, REPLACE now (+5 s), REPLACE visitedAt, REASON, QUERY canReach,
QUERY IND CLASS URGENT — measured for topostore through ``ArmorService.call`` in-process and for
warm Pellet (one OWL API ontology and one Pellet reasoner kept alive in a JVM, REASON =
``reasoner.flush()``, as aRMOR runs it) on the same maps and moves, answers compared after every
step; then topostore alone on maps of 1,000 to 100,000 locations.

Modules, one concept each: ``maps`` (the map files), ``walk`` (the moves and the expected
answers), ``armor_robot`` (topostore's step), ``warm_pellet`` + ``pellet/PelletStep.java`` (the
peer), ``timing`` (medians, p95, RSS), ``compare`` and ``scale`` (one size each, in a process of
its own), ``report`` (machine, table, ratios, CSV, plot).
"""
