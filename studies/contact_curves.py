"""Paper Fig. 1: force-indentation loops of the five laws (same as ``femoat contact-curves``)."""

import sys

from femoat.cli import main

if __name__ == "__main__":
    sys.exit(main(["contact-curves", *sys.argv[1:]]))
