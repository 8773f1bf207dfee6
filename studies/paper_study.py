"""The paper study: 5 contact laws × 2 walls under Erzincan N-S (Figs. 4-7, summary table).

    python studies/paper_study.py [--damping consistent] [--quick] [--out folder]

Same as ``femoat paper``; nothing runs at import.
"""

import sys

from femoat.cli import main

if __name__ == "__main__":
    sys.exit(main(["paper", *sys.argv[1:]]))
