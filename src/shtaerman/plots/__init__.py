"""Figures drawn from study outcomes; nothing here computes a result.

- :mod:`.style`: colours, rc style, SI prefixes and saving shared by the matplotlib figures;
- :mod:`.formats`: the figure formats (PNG, and SVG or PDF beside it) and ``--figure-format``;
- :mod:`.labels`: readable names, units and per cent of the quantities figures show;
- :mod:`.curves`: force against depth, the pressure profile, mesh convergence;
- :mod:`.impact`: the impact histories (the paper's Figs. 3 and 4);
- :mod:`.ateb`: the Ateb functions against the paper's Tables 1-2;
- :mod:`.render`: the off-screen pyvista plotter (the one place one is made);
- :mod:`.fields`: which FEM fields can be drawn and how they are coloured;
- :mod:`.sections`: the r-z section pictures; :mod:`.revolved`: the 3D cut-away;
- :mod:`.gallery`: the figures of a verification run and their captions.
"""
