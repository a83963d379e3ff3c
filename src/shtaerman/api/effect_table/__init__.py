"""The effect table (``shtaerman effects``, :func:`shtaerman.effects`): which effect of a
problem (the pad, the waves, finite strain, viscoelasticity, friction) moves the impact's
P_max, x_max, t_contact and e away from the paper's quasi-static values, and by how much.

- :mod:`.variants`: the effects and the variants that switch them off;
- :mod:`.run`: :func:`effects`, which runs the variants;
- :mod:`.types`: a run, a cell and what the figure reads of a table (for both);
- :mod:`.table`: :class:`EffectTable`, the changes, the interaction and the dominant effect;
- :mod:`.report`: the table as text, markdown and CSV;
- :mod:`.figure`: the table as a figure (a panel per quantity, a bar per run).
"""

from .run import effects as effects
from .table import EffectTable as EffectTable

__all__ = ["EffectTable", "effects"]
