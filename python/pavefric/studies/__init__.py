"""The maintainers' studies and reports, apart from the library.

Each regenerates a page of docs/ from runs of the library (the commands are
``python -m pavefric COMMAND``, see ``python -m pavefric --help``):
``accuracy`` (docs/accuracy.md), ``bench``, ``bench_io``, ``bench_mpi``
(docs/performance.md, docs/cluster.md), ``validation`` and
``reference_surfaces`` (docs/validation.md), ``speed_gradient``
(docs/speed_gradient.md), ``rubber_report`` (docs/rubber.md),
``energy_report`` (docs/model.md's figures), ``docs`` (docs/inputs.md,
docs/outputs.md), with ``reports`` their shared page writers.

The library (``pavefric``: scenes, runs, results, profiles, calibration,
rubber) never imports this package; these modules use the library's public
functions only, so they show what a user's study would look like.
"""
