"""What the checkpoints of a run cost: the paper scenes written with checkpoints (cases.run.checkpoint) against the
run's wall time.

    .venv/bin/python benchmarks/checkpoint.py [--repeats 5] [--stresses] [-o DIR]

Each of the four paper scenes (rolling parallel / perpendicular to Ft, f_t = 0.46 / 0.77, dx = dW = 0.2 mm, 10
periods, 11 checkpoints: end of loading and every period end) is run --repeats times in this process after a
warm-up, writing its file. Reported, as medians: the run's wall time, the time spent writing checkpoints (measured
around each write, summary `checkpoint_time`) and its share of the run (target < 5 %), the time of the final write,
and the wall time of the same run kept in memory (no file, no checkpoints) for comparison. With --stresses the runs
also compute the subsurface stresses of each stored step as they go (`run --stresses`, default depths; written to
step files beside the run file, never into the checkpoints): the checkpoints must cost what they cost without.
"""
import argparse
import os
from pathlib import Path
import statistics
import tempfile
import time

from rollcontact.cases import api

import _record

HERE = Path(__file__).resolve().parent
SCENES = [("parallel", 0.46, {"motion.angle": 0}), ("perpendicular", 0.46, {}),
          ("parallel", 0.77, {"motion.angle": 0, "load.ft": 0.77}), ("perpendicular", 0.77, {"load.ft": 0.77})]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    parser.add_argument("--repeats", type=int, default=5, help="timed runs per scene (median; default 5)")
    parser.add_argument("--stresses", action="store_true", help="runs with stresses=True (run --stresses)")
    _record.add_output(parser)
    args = parser.parse_args(argv)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for setting, f_t, overrides in SCENES:
            scene = api.load_scene(overrides=overrides)
            api.run(scene, Path(tmp) / "warm.h5", overwrite=True, stresses=args.stresses)
            walls, shares, cps, finals, memory = [], [], [], [], []
            for i in range(args.repeats):
                t = time.perf_counter()
                r = api.run(scene, Path(tmp) / "run.h5", overwrite=True, stresses=args.stresses)
                total = time.perf_counter() - t
                walls.append(r.wall_time)
                cps.append(r.summary["checkpoint_time"])
                shares.append(r.summary["checkpoint_time"] / r.wall_time)
                finals.append(total - r.wall_time)
                memory.append(api.run(scene).wall_time)
            row = dict(setting=setting, f_t=f_t, checkpoints=r.summary["checkpoints"],
                       wall_s=statistics.median(walls), checkpoint_s=statistics.median(cps),
                       share=statistics.median(shares), final_write_s=statistics.median(finals),
                       in_memory_wall_s=statistics.median(memory), file_mb=os.path.getsize(r.path) / 1e6)
            rows.append(row)
            print(f"{setting:13s} f_t = {f_t}: wall {row['wall_s']:.2f} s, {row['checkpoints']} checkpoints "
                  f"{row['checkpoint_s'] * 1e3:.0f} ms = {100 * row['share']:.1f} %, final write "
                  f"{row['final_write_s'] * 1e3:.0f} ms, in memory {row['in_memory_wall_s']:.2f} s, "
                  f"file {row['file_mb']:.1f} MB", flush=True)
    result = {"repeats": args.repeats, "stresses": args.stresses, "rows": rows}
    _record.write("checkpoint_stresses" if args.stresses else "checkpoint", result, args.output)


if __name__ == "__main__":
    main()
