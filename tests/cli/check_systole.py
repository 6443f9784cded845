#!/usr/bin/python3
"""Checks summary.json's circulation.systole_step of a coupled beat: it is the output
step (1 = after the first time step, as displacement_00001.vtu) with the highest LV
pressure among the steps of the last period, its time is that step's, and that pressure
is the beat's reported peak LV pressure.

    check_systole.py SUMMARY_JSON"""
import json
import sys


def main():
    s = json.load(open(sys.argv[1]))
    c = s["circulation"]
    cav = c["systole_cavity"]
    hist = s["history"]
    t_end, period = hist[-1]["time"], c["period"]
    window = [i for i in range(1, len(hist) + 1) if hist[i - 1]["time"] >= t_end - period * (1 - 1e-9)]
    p = {i: hist[i - 1]["circulation"][cav]["pressure"] for i in window}
    best = max(window, key=lambda i: p[i])
    peak = c["cavities"][cav]["peak_pressure"]
    print(f"systole_step {c['systole_step']} (t = {c['systole_time']}), expected {best} "
          f"(p = {p[best]:.6g} Pa, reported peak {peak:.6g} Pa)")
    ok = (c["systole_step"] == best and abs(c["systole_time"] - hist[best - 1]["time"]) <= 1e-12
          and abs(p[best] - peak) <= 1e-9 * abs(peak) and best not in (window[0], window[-1]))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
