#!/usr/bin/python3
"""ahhs-report: figures and a Markdown summary for ahhs-evolve runs (docs/analysis.md).

  ahhs-report RUN_DIR... -o OUT_DIR [--no-replay]
  ahhs-report neighbourhood GENOME_OR_RUN_DIR [--mutants 35] -o OUT_DIR [scenario options]
  ahhs-report study STUDY_DIR_OR_EXPORT -o OUT_DIR (study_report.py)
  ahhs-report steps GENOME_OR_RUN... -o OUT_DIR (step_report.py)
  ahhs-report compare STUDY_REPORT_DIR... -o OUT_DIR (compare_report.py)
  ahhs-report judge STUDY_EXPORT... --cache DIR -o OUT_DIR (judge_report.py)

This file only parses the command line and dispatches. The modules form a stack without cycles:
report_lib (runs, statistics, figures, replays) < run_report (runs, neighbourhood), claims_lib
(how a claim is judged) < study_report, step_report, compare_report < judge_report (which uses
step_report's rule) < ahhs_report. A study's claims live beside its plan
(studies/paper-2010-claims.py).

Reads each run's SQLite database directly (Python's sqlite3), replays the best genome of the
first run with ahhs-replay for the per-tick figures, and writes every figure as PNG and SVG.
Statistics: two-sided Wilcoxon rank-sum (Mann-Whitney U) tests from scipy, exact for small
samples without ties.
"""
import argparse
import os
import sys

import compare_report
import judge_report
import report_lib
import step_report
import study_report
from report_lib import ReportError, UsageError
from run_report import report_neighbourhood, report_runs


def main(argv):
    if len(argv) >= 2 and argv[0] == "--bin":  # the build's wrapper passes its bin directory
        os.environ.setdefault("AHHS_BIN", argv[1])
        argv = argv[2:]
    if argv and argv[0] == "--version":  # the wrapper passes the build's version
        print(f"ahhs-report {os.environ.get('AHHS_VERSION', 'unknown')}")
        return 0
    if argv and argv[0] == "study":
        return study_report.main(argv[1:])
    if argv and argv[0] == "steps":
        return step_report.main(argv[1:])
    if argv and argv[0] == "compare":
        return compare_report.main(argv[1:])
    if argv and argv[0] == "judge":
        return judge_report.main(argv[1:])
    if argv and argv[0] == "neighbourhood":
        p = argparse.ArgumentParser(prog="ahhs-report neighbourhood",
                                    description="fitness of single mutants of a genome")
        p.add_argument("genome", help="genome file, or a run directory (its best genome)")
        p.add_argument("--mutants", type=int, default=35)
        p.add_argument("--mutant-seed", type=int, default=1)
        p.add_argument("--scenario", default="gait", choices=["gait", "pendulum"])
        report_lib.add_docking_option(p)
        p.add_argument("--modules", type=int, default=5)
        p.add_argument("--duration", type=float, default=0)
        p.add_argument("--seed", type=int, default=1, help="episode seed (genome files)")
        p.add_argument("--physics", default="",
                       help="the physics version to replay with (genome files; default this "
                            "build's, as ahhs-replay --physics)")
        p.add_argument("-o", "--out", required=True)
        p.add_argument("--overwrite", action="store_true", help="replace a report in --out")
        p.add_argument("--bin", help="directory of ahhs-replay")
        args = p.parse_args(argv[1:])
        report_neighbourhood(args)
        return 0
    p = argparse.ArgumentParser(
        prog="ahhs-report", description="figures and a summary for ahhs-evolve runs",
        epilog="also: ahhs-report neighbourhood GENOME_OR_RUN_DIR -o DIR [--mutants N]: the "
               "mutation neighbourhood of a genome (ahhs-report neighbourhood --help); "
               "ahhs-report study STUDY_DIR -o DIR: a study against the paper's claims; "
               "ahhs-report steps GENOME... -o DIR: the gait's physics step judged by "
               "post-evaluated distributions; ahhs-report compare REPORT_DIR... -o DIR: the "
               "paper's claims side by side across study reports; ahhs-report judge EXPORT... "
               "--cache DIR -o DIR: how a study's bests hold under other steps, command delays "
               "and bent starts")
    p.add_argument("runs", nargs="+",
                   help="run directories, or runs of a study export (ahhs-study export)")
    p.add_argument("-o", "--out", required=True, help="output directory")
    p.add_argument("--overwrite", action="store_true", help="replace a report in --out")
    p.add_argument("--no-replay", action="store_true",
                   help="skip the replay of the best genome (and its per-tick figures)")
    p.add_argument("--bin", help="directory of ahhs-replay")
    report_runs(p.parse_args(argv))
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except UsageError as e:
        print(f"ahhs-report: {e}", file=sys.stderr)
        sys.exit(2)
    except ReportError as e:
        print(f"ahhs-report: {e}", file=sys.stderr)
        sys.exit(1)
