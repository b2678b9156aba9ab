"""Reasoning-latency benchmarks: ``python -m benchmarks [--quick] [--skip-100k]`` (``make bench``).

One robot step — REPLACE isIn, REPLACE now (+5 s), REPLACE visitedAt, REASON, QUERY canReach,
QUERY IND CLASS URGENT — measured for topostore through ``ArmorService.call`` in-process and for
warm Pellet (one OWL API ontology and one Pellet reasoner kept alive in a JVM whose JIT was warmed
on a scratch copy of the map, REASON = ``reasoner.flush()``, as aRMOR runs it) on the same maps and
moves, answers compared after every step; then topostore alone on maps of 1,000 to 100,000
locations; the drift of the step over 4,000 steps; the step's HTTP requests on ``oxigraph serve``;
full REASON against reasonable, owlrl and Pellet on the same files.

Modules, one concept each: ``maps`` (the map files), ``walk`` (the moves and the expected
answers), ``armor_robot`` (topostore's step), ``warm_pellet`` + ``pellet/PelletStep.java`` (the
peer), ``timing`` (medians, p95, RSS), ``compare`` and ``scale`` (one size each, in a process of
its own), ``drift`` (a long walk), ``remote`` + ``http_count`` (the step on a SPARQL server,
requests counted at the transport), ``full`` + ``tbox`` (full REASON per engine, the tutorial-style
TBox), ``full_floor`` + ``full_floor_closure`` (the floor of a full REASON on the bare store, held
against topostore's closure), ``report`` (machine, step table, issue 20's step targets, CSV, plot) and ``tables`` (the
drift, remote and full-REASON tables with their targets).
"""
