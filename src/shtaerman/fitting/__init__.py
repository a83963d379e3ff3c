"""Fitting the rubber's constants to a measurement (``shtaerman fit``, :func:`fit`).

- :mod:`.data`: the measurement's CSV, its units and its checks;
- :mod:`.models`: the exact quasi-static forward models;
- :mod:`.engine`: least squares, intervals and identifiability;
- :mod:`.result`: the :class:`FitResult` (``fit --json``);
- :mod:`.run`: :func:`fit` itself.
"""
