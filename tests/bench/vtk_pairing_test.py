"""How bench/vtk_bench.py pairs VTK's runs with cutaway's, and how bench/report.py
prints them, lays out the frame table and writes its sections (no VTK needed:
only the arithmetic and the text are tested).

Usage: python3 tests/bench/vtk_pairing_test.py REPOSITORY_ROOT
"""
import json
import os
import subprocess
import sys
import tempfile
import unittest

BENCH = os.path.join(sys.argv.pop(1) if len(sys.argv) > 1 else ".", "bench")
sys.path.insert(0, BENCH)
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


def frame_record(dataset, d, method, alignment, median):
    return {"renderer": "cutaway", "dataset": dataset, "dims": [8, 9, 10], "slice_spacing": d,
            "method": method, "alignment": alignment,
            "operator": "none" if alignment == "none" else "peeler", "ms_median": median,
            "ms_min": median, "ms_max": median, "fps": 1000.0 / median}


class FrameTable(unittest.TestCase):
    def test_each_time_lands_in_its_rows_method_and_alignment_column(self):
        records = [frame_record("tiny", d, m, a, t) for d, m, a, t in [
            (1.0, "slicing", "none", 300), (1.0, "slicing", "surface", 400),
            (1.0, "raycast", "none", 101), (1.0, "raycast", "surface", 202),
            (0.5, "slicing", "none", 600), (0.5, "raycast", "surface", 404)]]
        table = report.frame_rows(records)
        self.assertEqual(table[0], "| dataset | dims | operator | d | ray cast: none | surface |"
                                   " slicing: none | surface |")
        self.assertEqual(table[2], "| tiny | 8x9x10 | peeler | 1.0 | 101 | 202 | 300 | 400 |")
        # A combination that was not run is shown as missing, not shifted.
        self.assertEqual(table[3], "| tiny | 8x9x10 | peeler | 0.5 | - | 404 | 600 | - |")
        self.assertEqual(len(table), 4)

    def test_a_gpus_short_frames_keep_a_decimal(self):
        records = [frame_record("tiny", 1.0, "raycast", "none", 5.06),
                   frame_record("tiny", 1.0, "raycast", "axis", 111.1)]
        self.assertEqual(report.frame_rows(records)[2],
                         "| tiny | 8x9x10 | peeler | 1.0 | 5.1 | 111 |")

    def test_turntables_and_vtk_are_not_frames(self):
        records = [frame_record("tiny", 1.0, "raycast", "none", 100),
                   dict(frame_record("tiny", 1.0, "slicing", "surface", 50), kind="turntable"),
                   dict(vtk_record(1.0, 70, 60, 80), method="raycast", alignment="axis")]
        self.assertEqual(report.frame_rows(records)[0],
                         "| dataset | dims | operator | d | ray cast: none |")


class Sections(unittest.TestCase):
    PAGE = ("intro\n<!-- results:begin -->\nCPU\n<!-- results:end -->\nmiddle\n"
            "<!-- results-gpu:begin -->\nGPU\n<!-- results-gpu:end -->\nend\n")

    def run_report(self, page, *section):
        with tempfile.TemporaryDirectory() as tmp:
            results, markdown = os.path.join(tmp, "r.json"), os.path.join(tmp, "p.md")
            with open(results, "w") as f:
                json.dump([frame_record("tiny", 1.0, "raycast", "none", 42)], f)
            with open(markdown, "w") as f:
                f.write(page)
            done = subprocess.run([sys.executable, os.path.join(BENCH, "report.py"), results,
                                   markdown, *section], capture_output=True, text=True)
            with open(markdown) as f:
                return done, f.read()

    def test_only_the_named_section_is_written(self):
        done, page = self.run_report(self.PAGE, "--section", "results-gpu")
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("<!-- results:begin -->\nCPU\n<!-- results:end -->\nmiddle\n", page)
        self.assertNotIn("\nGPU\n", page)
        self.assertIn("| tiny | 8x9x10 | none | 1.0 | 42.0 |", page)
        self.assertTrue(page.startswith("intro\n") and page.endswith("-->\nend\n"))

    def test_make_bench_writes_the_results_section(self):
        done, page = self.run_report(self.PAGE)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertNotIn("\nCPU\n", page)
        self.assertIn("\nGPU\n", page)

    def test_a_page_without_the_section_is_refused_and_left_alone(self):
        done, page = self.run_report(self.PAGE, "--section", "results-tpu")
        self.assertEqual(done.returncode, 2)
        self.assertIn("results-tpu:begin", done.stderr)
        self.assertEqual(page, self.PAGE)


if __name__ == "__main__":
    unittest.main()
