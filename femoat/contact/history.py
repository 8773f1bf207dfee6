"""The layout of a contact's history array, shared by the kernels and the Python side (numba
reads module-level integers as compile-time constants). The laws' integer codes are not here:
:mod:`femoat.contact.laws` numbers the kernel families in registry order.

History ``h`` (length :data:`N_HISTORY`, float64), one per contact:

* ``h[H_V0]``: approach velocity δ̇₀ captured at gap closure [in/s] (Hertzdamp);
* ``h[H_DMAX]``: largest indentation δ_m of the episode so far [in] (Muthukumar);
* ``h[H_D_LAST]``, ``h[H_F_LAST]``: for the implicit time stepping only, the indentation δ_n at
  the last committed step [in] and the elastic force f̃_n that step used there [kip] (the
  discrete gradient of :mod:`femoat.contact.hertz`).
"""

H_V0, H_DMAX, H_D_LAST, H_F_LAST = 0, 1, 2, 3
N_HISTORY = 4
