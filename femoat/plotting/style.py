"""Shared plotting conventions: one colour and line style per contact law."""

LAW_STYLE = {
    "E": dict(color="#1f77b4", linestyle="-", label="E  linear elastic"),
    "V": dict(color="#ff7f0e", linestyle="--", label="V  Kelvin-Voigt"),
    "J": dict(color="#2ca02c", linestyle="-.", label="J  Jankowski"),
    "H": dict(color="#d62728", linestyle=":", label="H  Hertzdamp"),
    "M": dict(color="#9467bd", linestyle=(0, (5, 1, 1, 1)), label="M  Muthukumar bilinear"),
}


def pyplot():
    """matplotlib.pyplot on the off-screen Agg backend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt
