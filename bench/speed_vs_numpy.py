#!/usr/bin/env python3
"""End-to-end speed of `sigmatau adev` (exact, in memory, intervals included) against a plain
numpy vectorised OADEV on the same samples, run alternately in one sitting (issue 25).

For each size a raw f64 file of white + random-walk FM rate samples (seeded) is written to a
temporary directory. Each round runs, in turn and each in its own process under
/usr/bin/time -v (page cache warm after the first round):
  - sigmatau adev FILE --binary f64 --channels 1 --rate 100 --stat oadev --taus octave
    --format json, with the default threads and with --threads 1;
  - numpy: np.fromfile, phase = cumsum with a leading 0, then per octave m one vectorised second
    difference x[2m:] - 2 x[m:-m] + x[:-2m] and its mean square (as allantools' oadev does,
    without intervals or noise identification);
  - every statistic alone and the combination oadev,mdev,ohdev,totdev (default threads), at
    the sizes given by --stat-sizes;
  - `analyze` on a 3 h, 1 kHz, 6-channel f32 log (65 M values, simulated from the ADIS16465
    sheet) with --spec, report, plots and filter files (--analyze-runs rounds; issue 25 asks
    <= 4 s), and the built-in `demo`; with --baseline BIN the demo also runs on that build,
    alternately.
The medians of --runs rounds (wall, user, system, peak RSS) go to a Markdown table, with the
ratio numpy wall / sigmatau wall and the machine's CPU model and load.

Usage: bench/speed_vs_numpy.py --sigmatau build/cli/sigmatau [--sizes 1e6,1e7,1e8] [--runs 5]
       [--stat-sizes 1e7] [--stat-runs 3] [--analyze-runs 3] [--baseline BIN]
       [--out bench/results_speed.md] [--tmp DIR]
Needs python3 with numpy and /usr/bin/time (GNU). The 1e8 file takes 800 MB in --tmp.
"""
import argparse
import os
import platform
import statistics
import subprocess
import sys
import tempfile

NUMPY_OADEV = r"""
import sys
import numpy as np
y = np.fromfile(sys.argv[1], dtype='<f8')
x = np.empty(y.size + 1)
x[0] = 0.0
np.cumsum(y, out=x[1:])
n = x.size
m = 1
out = []
while 2 * m < n:
    d = x[2 * m:] - 2 * x[m:-m] + x[:-2 * m]
    out.append((m, float(np.sqrt(np.mean(d * d) / 2) / m)))
    m *= 2
print(len(out))
"""

STATS = ["oadev", "mdev", "tdev", "hdev", "ohdev", "totdev", "oadev,mdev,ohdev,totdev"]


def timed(cmd):
    """Runs cmd under /usr/bin/time -v; returns (wall, user, sys, peak RSS bytes)."""
    with tempfile.NamedTemporaryFile("r", suffix=".time") as t:
        r = subprocess.run(["/usr/bin/time", "-v", "-o", t.name] + cmd,
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if r.returncode != 0:
            sys.exit("failed: " + " ".join(cmd) + "\n" + r.stderr)
        fields = {}
        for line in t.read().splitlines():
            key, _, value = line.strip().rpartition(": ")
            fields[key] = value
    wall = fields["Elapsed (wall clock) time (h:mm:ss or m:ss)"]
    seconds = 0.0
    for part in wall.split(":"):
        seconds = seconds * 60 + float(part)
    return (seconds, float(fields["User time (seconds)"]), float(fields["System time (seconds)"]),
            int(fields["Maximum resident set size (kbytes)"]) * 1024)


def write_samples(path, n, seed):
    import numpy as np
    rng = np.random.default_rng(seed)
    with open(path, "wb") as f:
        walk = 0.0
        for start in range(0, n, 10_000_000):
            k = min(10_000_000, n - start)
            w = rng.standard_normal(k)
            rw = walk + np.cumsum(rng.standard_normal(k)) * 1e-3
            walk = rw[-1]
            (w + rw).astype("<f8").tofile(f)


def machine():
    model = platform.processor() or "?"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{model}, {os.cpu_count()} logical CPUs, {platform.system()} {platform.release()}"


def median_row(samples):
    return tuple(statistics.median(s[i] for s in samples) for i in range(4))


def label(n):
    return f"1e{len(str(n)) - 1}" if str(n).strip("0") == "1" else str(n)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--sigmatau", required=True)
    p.add_argument("--sizes", default="1e6,1e7,1e8")
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("--stat-sizes", default="1e7")
    p.add_argument("--stat-runs", type=int, default=3)
    p.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "results_speed.md"))
    p.add_argument("--tmp", default=None)
    p.add_argument("--analyze-runs", type=int, default=3)
    p.add_argument("--baseline", default=None)
    a = p.parse_args()
    sizes = [int(float(s)) for s in a.sizes.split(",") if s]
    stat_sizes = [int(float(s)) for s in a.stat_sizes.split(",") if s]
    tmp = tempfile.mkdtemp(prefix="sigmatau_speed_", dir=a.tmp)
    numpy_script = os.path.join(tmp, "numpy_oadev.py")
    with open(numpy_script, "w") as f:
        f.write(NUMPY_OADEV)
    load_before = os.getloadavg()
    rows = []  # (size, what, (wall, user, sys, rss), numpy wall)
    stat_rows = []
    chain_rows = []  # (what, (wall, user, sys, rss))
    try:
        for n in sorted(set(sizes) | set(stat_sizes)):
            path = os.path.join(tmp, f"x{n}.f64")
            write_samples(path, n, 2500 + n % 1000)
            adev = [a.sigmatau, "adev", path, "--binary", "f64", "--channels", "1", "--rate",
                    "100", "--taus", "octave", "--format", "json"]
            if n in sizes:
                runs = {"default": [], "one": [], "numpy": []}
                for _ in range(a.runs):
                    runs["default"].append(timed(adev + ["--stat", "oadev"]))
                    runs["numpy"].append(timed([sys.executable, numpy_script, path]))
                    runs["one"].append(timed(adev + ["--stat", "oadev", "--threads", "1"]))
                numpy_wall = median_row(runs["numpy"])[0]
                rows.append((n, "sigmatau oadev, default threads", median_row(runs["default"]), numpy_wall))
                rows.append((n, "sigmatau oadev, --threads 1", median_row(runs["one"]), numpy_wall))
                rows.append((n, "numpy vectorised OADEV (no intervals)", median_row(runs["numpy"]), numpy_wall))
                print(f"{label(n)} done", file=sys.stderr)
            if n in stat_sizes:
                per = {s: [] for s in STATS}
                for _ in range(a.stat_runs):
                    for s in STATS:
                        per[s].append(timed(adev + ["--stat", s]))
                for s in STATS:
                    stat_rows.append((n, s, median_row(per[s])))
                print(f"{label(n)} statistics done", file=sys.stderr)
            os.remove(path)
        if a.analyze_runs > 0:
            log = os.path.join(tmp, "imu3h.f32")
            subprocess.run([a.sigmatau, "simulate", "--spec", "adi_adis16465", "--sensors",
                            "gyro,accel", "--rate", "1000", "--duration", "3h", "--format", "f32",
                            "-o", log, "--force"], check=True, stdout=subprocess.DEVNULL)
            report = os.path.join(tmp, "report")
            analyze = [a.sigmatau, "analyze", log, "--binary", "f32", "--channels", "6",
                       "--gyro", "c0,c1,c2", "--accel", "c3,c4,c5", "--rate", "1000",
                       "--spec", "adi_adis16465", "-o", report, "--force"]
            demo = ["demo", "-o", os.path.join(tmp, "demo"), "--force"]
            runs = {"analyze": [], "demo": [], "demo_base": []}
            for _ in range(a.analyze_runs):
                runs["analyze"].append(timed(analyze))
                runs["demo"].append(timed([a.sigmatau] + demo))
                if a.baseline:
                    runs["demo_base"].append(timed([a.baseline] + demo))
            chain_rows.append(("analyze, 3 h x 6 channels at 1 kHz, f32 (65 M values), --spec",
                               median_row(runs["analyze"])))
            chain_rows.append(("demo (10 h x 6 channels at 100 Hz, 21.6 M values)", median_row(runs["demo"])))
            if a.baseline:
                chain_rows.append(("demo, the --baseline build",
                                   median_row(runs["demo_base"])))
            print("analyze done", file=sys.stderr)
    finally:
        for root, dirs, files in os.walk(tmp, topdown=False):
            for name in files:
                os.remove(os.path.join(root, name))
            for name in dirs:
                os.rmdir(os.path.join(root, name))
        os.rmdir(tmp)
    load_after = os.getloadavg()
    out = []
    out.append("# End-to-end speed: `sigmatau adev` against numpy\n")
    out.append("Written by `bench/speed_vs_numpy.py` (see its docstring for what runs). Machine: "
               f"{machine()}; load average {load_before[0]:.1f} before, {load_after[0]:.1f} after "
               "(a shared VM: other jobs ran beside these, so wall times carry their share of "
               "waiting; user + system is the work done).\n")
    out.append("One channel of white + random-walk FM rate samples, raw f64, page cache warm; "
               "sigmatau exact in memory, octave taus, intervals included, JSON to /dev/null. "
               f"Medians of {a.runs} alternating rounds.\n")
    out.append("| samples | run | wall [s] | user [s] | system [s] | peak RSS [MB] | RSS / sample [B] | numpy wall / this wall |")
    out.append("|---|---|---|---|---|---|---|---|")
    for n, what, (wall, user, sys_, rss), numpy_wall in rows:
        out.append(f"| {label(n)} | {what} | {wall:.3f} | {user:.3f} | {sys_:.3f} | {rss / 1e6:.0f} | "
                   f"{rss / n:.1f} | {numpy_wall / wall:.2f} |")
    if stat_rows:
        out.append("")
        out.append(f"Each statistic, default threads, medians of {a.stat_runs} rounds; the last "
                   "column is the wall time over OADEV's in the same rounds.\n")
        out.append("| samples | --stat | wall [s] | user [s] | system [s] | peak RSS [MB] | / oadev |")
        out.append("|---|---|---|---|---|---|---|")
        for n, s, (wall, user, sys_, rss) in stat_rows:
            base = next(r[2][0] for r in stat_rows if r[0] == n and r[1] == "oadev")
            out.append(f"| {label(n)} | {s} | {wall:.3f} | {user:.3f} | {sys_:.3f} | {rss / 1e6:.0f} | {wall / base:.2f} |")
    if chain_rows:
        out.append("")
        out.append(f"The whole chain, default threads, medians of {a.analyze_runs} alternating rounds "
                   "(report, plots, filter files; page cache warm).\n")
        out.append("| run | wall [s] | user [s] | system [s] | peak RSS [MB] |")
        out.append("|---|---|---|---|---|")
        for what, (wall, user, sys_, rss) in chain_rows:
            out.append(f"| {what} | {wall:.2f} | {user:.2f} | {sys_:.2f} | {rss / 1e6:.0f} |")
    text = "\n".join(out) + "\n"
    with open(a.out, "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
