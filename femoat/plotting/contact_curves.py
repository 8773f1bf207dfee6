"""Paper Fig. 1: force-indentation loops of the five contact laws in one impact."""

import csv
import io

from femoat.atomic import atomic_path, write_text
from femoat.plotting.style import LAW_STYLE, pyplot


def plot_contact_curves(results, path, title=""):
    """Write the force-indentation loops and force histories of ``results`` to a PNG."""
    plt = pyplot()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.4), constrained_layout=True)
    for kind, r in results.items():
        style = LAW_STYLE[kind]
        ax1.plot(r.indentation, r.force, lw=1.6, **style)
        ax2.plot(r.time * 1e3, r.force, lw=1.6, **style)
    ax1.set_xlabel("indentation δ [in]")
    ax1.set_ylabel("contact force [kip]")
    ax1.set_title("force-indentation")
    ax2.set_xlabel("time since gap closure [ms]")
    ax2.set_ylabel("contact force [kip]")
    ax2.set_title("force history")
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
        ax.set_xlim(left=0)
        ax.set_ylim(bottom=0)
    ax1.legend(fontsize=8)
    if title:
        fig.suptitle(title)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=150)
    plt.close(fig)


def write_contact_curves_csv(results, path):
    """Write the histories as a long CSV: law, time [s], indentation [in], rate [in/s], force
    [kip], wall displacement [in]."""
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(["law", "time_s", "indentation_in", "indentation_rate_in_per_s", "force_kip",
                "wall_displacement_in"])
    for kind, r in results.items():
        for row in zip(r.time, r.indentation, r.indentation_rate, r.force, r.wall_displacement):
            w.writerow([kind, *(f"{x:.10g}" for x in row)])
    write_text(path, buf.getvalue())
