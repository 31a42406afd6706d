#!/usr/bin/env python3
"""Restart-from-ours figures (issue 9 item 8): of our Solved answers (a `reconfig sweep
--write-answers` file), how many the oracle lowers by more than 0.5 % when IPOPT is restarted
from them (our point was not a local minimum: not stationary, or a saddle), and how many sit
more than 0.5 % above the oracle's own best while the restart stays put (a genuine other local
minimum).

Usage: python3 tests/oracle/planner_a_restart_report.py OURS.jsonl fixtures/golden/planner-a-oracle.jsonl
"""

import json
import sys

GAP = 5e-3


def main():
    ours = {}
    for line in open(sys.argv[1]):
        if line.strip():
            a = json.loads(line)
            ours[a["index"]] = a
    golden = [json.loads(line) for line in open(sys.argv[2]) if line.strip()]
    golden = [g for g in golden if "header" not in g]
    solved = lowered = other_min = above = 0
    lowered_list, other_list = [], []
    for g in golden:
        a = ours.get(g["index"])
        if not g["solved"] or a is None or a.get("status") != "Solved":
            continue
        solved += 1
        j = a["cost"]
        if (j - g["cost"]) / g["cost"] > GAP:
            above += 1
        r = g.get("ours_restart") or {}
        # A restart identical to one of the oracle's own starts was not re-run: it stays put.
        rj = r.get("cost") if r.get("feasible") else None
        if rj is not None and (j - rj) / rj > GAP:
            lowered += 1
            lowered_list.append((g["index"], g["family"], j, rj))
        elif (j - g["cost"]) / g["cost"] > GAP:
            other_min += 1
            other_list.append((g["index"], g["family"], j, g["cost"]))
    print(f"our Solved answers with an oracle answer: {solved}")
    print(f"  > 0.5 % above the oracle's best: {above}")
    print(f"  lowered by > 0.5 % when IPOPT restarts from ours (not a local minimum): {lowered}")
    for row in lowered_list:
        print("    index %d %s: ours %.6f, restart %.6f (%.2f %%)" % (*row, 100 * (row[2] - row[3]) / row[3]))
    print(f"  restart stays, oracle's own best lower by > 0.5 % (another local minimum): {other_min}")
    for row in other_list:
        print("    index %d %s: ours %.6f, oracle %.6f (%.2f %%)" % (*row, 100 * (row[2] - row[3]) / row[3]))


if __name__ == "__main__":
    main()
