"""Ground motions: records, readers, the FEMA P695 sets, the paper's Erzincan motion, spectra.

Acceleration is carried in g (as published) on a uniform time grid t = n*dt; see
:mod:`femoat.ground_motions.record` for the conventions.
"""

from .erzincan import PAPER_PGA, erzincan_ns, erzincan_paper
from .fema import FEMA_P695_SETS, FemaP695Record, fema_p695_record, fema_p695_records
from .pair import (
    RecordPair,
    RotDSpectrum,
    fema_p695_pair,
    p695_anchor_factor,
    read_at2_pair,
    rotd_spectrum,
)
from .peer import RecordFormatError, read_at2, read_text
from .record import GroundMotion
from .spectrum import ResponseSpectrum, response_spectrum

__all__ = [
    "FEMA_P695_SETS",
    "PAPER_PGA",
    "FemaP695Record",
    "GroundMotion",
    "RecordFormatError",
    "RecordPair",
    "ResponseSpectrum",
    "RotDSpectrum",
    "erzincan_ns",
    "erzincan_paper",
    "fema_p695_pair",
    "fema_p695_record",
    "fema_p695_records",
    "p695_anchor_factor",
    "read_at2",
    "read_at2_pair",
    "read_text",
    "response_spectrum",
    "rotd_spectrum",
]
