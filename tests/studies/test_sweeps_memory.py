"""A serial study keeps every variant while it runs: a model keeps nothing of its analysis (the
assembly an analysis builds is the analysis's), so memory does not grow per point."""
import gc
import tracemalloc

import numpy as np

from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.studies import paths as P
from propwhirl.studies.sweeps import evaluate

SPEEDS = np.arange(10.0, 351.0, 20.0)


def test_a_point_keeps_little_of_its_analysis():
    m = wingtip_propeller_wing()
    evaluate((m, SPEEDS, 0.01, True, True, "reduced"))          # imports, lazy module caches
    variants = [P.set_values(m, {"propellers[0].propeller.f_theta": 5.0 + 0.1 * i})
                for i in range(20)]
    gc.collect()
    tracemalloc.start()
    try:
        for v in variants:
            evaluate((v, SPEEDS, 0.01, True, True, "reduced"))
        gc.collect()
        kept = tracemalloc.get_traced_memory()[0] / len(variants)
    finally:
        tracemalloc.stop()
    # the wing structure alone (3 dense 78 x 78 matrices) would be 146 kB per point
    assert kept < 20e3, f"{kept / 1e3:.1f} kB kept per point"


def test_a_model_analysed_again_gives_the_same_result():
    m = wingtip_propeller_wing()
    a = evaluate((m, SPEEDS, 0.01, True, True, "dense"))
    b = evaluate((m, SPEEDS, 0.01, True, True, "dense"))
    assert a == b
