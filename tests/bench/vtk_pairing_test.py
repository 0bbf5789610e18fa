"""How bench/vtk_bench.py pairs VTK's runs with cutaway's, and how bench/report.py
prints them (no VTK needed: only the arithmetic is tested).

Usage: python3 tests/bench/vtk_pairing_test.py REPOSITORY_ROOT
"""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(sys.argv.pop(1) if len(sys.argv) > 1 else ".", "bench"))
import report  # noqa: E402
import vtk_bench  # noqa: E402


def vtk_record(d, median, lo, hi):
    return {"renderer": "vtk", "dataset": "tiny", "slice_spacing": d, "ms_median": median,
            "ms_min": lo, "ms_max": hi, "fps": 1000.0 / median}


class MergeRounds(unittest.TestCase):
    def test_each_round_is_set_against_the_cutaway_runs_on_either_side(self):
        rounds = [[vtk_record(1.0, 100, 90, 110), vtk_record(0.5, 400, 390, 410)],
                  [vtk_record(1.0, 200, 180, 260), vtk_record(0.5, 300, 250, 320)],
                  [vtk_record(1.0, 150, 140, 170), vtk_record(0.5, 500, 480, 520)]]
        cutaway = [{1.0: 100, 0.5: 400}, {1.0: 300, 0.5: 400},
                   {1.0: 100, 0.5: 200}, {1.0: 200, 0.5: 400}]
        d1, d05 = vtk_bench.merge_rounds(rounds, cutaway)
        self.assertEqual(d1["ms_median"], 150)
        self.assertEqual((d1["ms_min"], d1["ms_max"]), (90, 260))
        self.assertAlmostEqual(d1["fps"], 1000.0 / 150, places=2)
        self.assertEqual(d1["rounds"], 3)
        self.assertEqual(d1["cutaway_paired_ms"], [100, 300, 100, 200])
        # 100 / mean(100, 300), 200 / mean(300, 100), 150 / mean(100, 200)
        self.assertEqual(d1["paired_ratios"], [0.5, 1.0, 1.0])
        self.assertEqual(d05["ms_median"], 400)
        self.assertEqual(d05["paired_ratios"], [1.0, 1.0, round(500 / 300, 3)])

    def test_without_cutaway_runs_there_is_nothing_to_pair(self):
        rounds = [[vtk_record(1.0, 100, 90, 110)], [vtk_record(1.0, 120, 100, 130)]]
        merged = vtk_bench.merge_rounds(rounds, [])
        self.assertEqual(merged[0]["ms_median"], 110)
        self.assertNotIn("paired_ratios", merged[0])
        # A cutaway run that lacks the row's spacing pairs nothing either.
        merged = vtk_bench.merge_rounds(rounds, [{1.0: 100}, {0.5: 100}, {1.0: 100}])
        self.assertNotIn("cutaway_paired_ms", merged[0])


class PairedRows(unittest.TestCase):
    def test_the_median_ratio_is_printed_beside_each_rounds(self):
        record = dict(vtk_record(1.0, 150, 90, 260), cutaway_paired_ms=[100, 300, 100, 200],
                      paired_ratios=[0.5, 1.0, 1.2])
        row = report.paired_rows([record])[-2]
        self.assertEqual(row, "| tiny | 1.0 | 150 | 100 / 300 / 100 / 200 | 0.50, 1.00, 1.20 |"
                              " 1.00 |")

    def test_a_record_of_one_round_gets_its_ratio_computed(self):
        record = dict(vtk_record(0.5, 150, 140, 160), cutaway_paired_ms=[100, 200])
        self.assertTrue(report.paired_rows([record])[-2].endswith("| 100 / 200 | 1.00 | 1.00 |"))


if __name__ == "__main__":
    unittest.main()
