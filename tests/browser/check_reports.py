#!/usr/bin/env python3
"""Renders every HTML report that `meridian demo` writes, and a
`meridian gravity points --report` page made here from a small synthetic
model, in headless Chromium and fails on a JavaScript error, a plot that did
not render, a missing section, a page that would need the network, or a PDF
that does not print.

Usage: check_reports.py --meridian build/meridian --out DIR --examples examples [--screenshots]
"""
import argparse
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update", "--disable-sync",
                  "--disable-quic", "--virtual-time-budget=20000", "--run-all-compositor-stages-before-draw",
                  "--enable-logging=stderr", "--v=0"]

# Sections each kind of report must have (HTML ids).
REQUIRED = {
    "campaign.html": ["result-sheet", "inputs", "result", "checks", "calibration", "line", "line-determination-1",
                      "notes"],
    "campaign-cjk.html": ["result-sheet", "result", "checks"],
    "orientations.html": ["result-sheet", "checks", "notes"],
    "orientations-cjk.html": ["result-sheet", "checks", "notes"],
    "spec-scenario-2.html": ["summary", "determination-1"],
    "tracking.html": ["summary", "determination-1"],
    "gravity-points.html": ["summary", "maps", "definitions"],
    "dov.html": ["summary", "profile", "innovations", "notes"],
    "dov-demo.html": ["summary", "profile", "innovations", "notes"],
    "nav-scenario-c.html": ["summary", "track", "errors", "bias", "rejected", "notes"],
    "nav-nbp1406.html": ["summary", "track", "errors", "bias", "notes"],
}

# Pages of jobs on real data outside the project (examples/nav-nbp1406.yaml reads
# ../shared/data/nmea): the demo skips them, saying so, when the data is absent.
REAL_DATA_JOBS = {"nav-nbp1406.html": "nav-nbp1406.yaml"}

# The gravity points page: a 20 x 20 grid of points over a region.
GRAVITY_POINTS = 400


def find_chromium():
    for name in (os.environ.get("MERIDIAN_CHROMIUM"), "chromium", "chromium-browser", "google-chrome"):
        if name and shutil.which(name):
            return shutil.which(name)
    return None


def check_page(chromium, path):
    errors = []
    html = open(path, encoding="utf-8").read()
    if re.search(r"<script[^>]+src=|<link[^>]+href=\"?https?:", html):
        errors.append("the page loads external resources (it must work offline)")
    with tempfile.TemporaryDirectory() as profile:
        run = subprocess.run([chromium, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", "--dump-dom",
                              "file://" + os.path.abspath(path)], capture_output=True, text=True, timeout=180)
    if run.returncode != 0:
        return [f"chromium exited with {run.returncode}: {run.stderr[-500:]}"]
    dom = run.stdout
    for line in run.stderr.splitlines():
        if "CONSOLE" in line and ("Uncaught" in line or "Error" in line):
            errors.append("console: " + line.strip())
    body = re.search(r"<body([^>]*)>", dom)
    attrs = dict(re.findall(r'([\w-]+)="([^"]*)"', body.group(1))) if body else {}
    if attrs.get("data-render-status") != "complete":
        errors.append("rendering did not complete (data-render-status missing)")
    else:
        expected = int(attrs.get("data-plots-expected", "0"))
        rendered = int(attrs.get("data-plots-rendered", "-1"))
        page_errors = json.loads(attrs.get("data-render-errors", "[]").replace("&quot;", '"'))
        if expected == 0:
            errors.append("the report has no plots")
        if rendered != expected:
            errors.append(f"{rendered} of {expected} plots rendered")
        errors += ["page: " + e for e in page_errors]
    svgs = len(re.findall(r"<svg[^>]*class=\"marks\"", dom))
    if body and svgs < int(attrs.get("data-plots-expected", "1")):
        errors.append(f"only {svgs} rendered SVG plots in the DOM")
    for section in REQUIRED.get(os.path.basename(path), []):
        if f'<section id="{section}"' not in dom:
            errors.append(f"missing section '{section}'")
    return errors


def write_gravity_report(meridian, out):
    """A synthetic model, a few hundred points and `gravity points --report`;
    returns an error message or None."""
    model = os.path.join(out, "gravity-model")
    synth = subprocess.run([meridian, "gravity", "synth-model", "--degree", "60", "--seed", "1", "--out", model],
                           capture_output=True, text=True)
    if synth.returncode != 0:
        return "meridian gravity synth-model: " + synth.stderr
    points = os.path.join(out, "gravity-points.csv")
    side = int(GRAVITY_POINTS ** 0.5)
    with open(points, "w", encoding="utf-8") as f:
        f.write("lat [deg],lon [deg],h [m]\n")
        for i in range(side):
            for j in range(side):
                f.write(f"{44 + 0.25 * i:.4f},{5 + 0.3 * j:.4f},{50 * (i + j)}\n")
    run = subprocess.run([meridian, "gravity", "points", "--model", model + ".gfc", "--input", points,
                          "-o", os.path.join(out, "gravity-points-out.csv"), "-q",
                          "--report", os.path.join(out, "gravity-points.html")], capture_output=True, text=True)
    if run.returncode != 0:
        return "meridian gravity points --report: " + run.stderr
    return None


def write_dov_report(meridian, out):
    """A simulated half-hour deflection-of-the-vertical line and `dov process --report`;
    returns an error message or None."""
    line, config = os.path.join(out, "dov-line.csv"), os.path.join(out, "dov.yaml")
    sim = subprocess.run([meridian, "dov", "simulate", "--hours", "0.5", "--seed", "2", "--out", line,
                          "--config", config], capture_output=True, text=True)
    if sim.returncode != 0:
        return "meridian dov simulate: " + sim.stderr
    run = subprocess.run([meridian, "dov", "process", config, "-q", "--report", os.path.join(out, "dov.html")],
                         capture_output=True, text=True)
    if run.returncode != 0:
        return "meridian dov process --report: " + run.stderr
    return None


def write_cjk_campaign_report(meridian, examples, out):
    """The example campaign with Chinese station and observer names, as a mine
    books them; returns an error message or None."""
    text = open(os.path.join(examples, "campaign.yaml"), encoding="utf-8").read()
    text = text.replace("C (shaft bottom)", "井底车场 C").replace("D (main drift)", "主巷 D")
    text = ('record: {observer: "王工", booker: "李工", computed_by: "张工", checked_by: "陈工", language: zh}\n'
            + text)
    book = os.path.join(out, "campaign-cjk.yaml")
    with open(book, "w", encoding="utf-8") as f:
        f.write(text)
    run = subprocess.run([meridian, "gyro", "campaign", book, "-q", "--report", os.path.join(out, "campaign-cjk.html")],
                         capture_output=True, text=True)
    if run.returncode != 0:
        return "meridian gyro campaign (CJK names): " + run.stderr
    if "井底车场 C" not in run.stdout:
        return "the text report lost the CJK station name"
    return None


def write_orientations_reports(meridian, out):
    """Two independent orientations of one line (`gyro simulate --mode campaign`, two seeds)
    combined with `gyro orientations --report`, in English and with Chinese labels; returns an
    error message or None."""
    books = []
    for seed in (21, 22):
        book = os.path.join(out, f"orientation-{seed}.yaml")
        sim = subprocess.run([meridian, "gyro", "simulate", "--mode", "campaign", "--seed", str(seed), "-o", book],
                             capture_output=True, text=True)
        if sim.returncode != 0:
            return "meridian gyro simulate --mode campaign: " + sim.stderr
        books.append(book)
    zh = []
    for book in books:
        text = open(book, encoding="utf-8").read()
        cjk = book[:-5] + "-cjk.yaml"
        with open(cjk, "w", encoding="utf-8") as f:
            f.write('record: {computed_by: "张工", checked_by: "陈工", language: zh}\n' + text)
        zh.append(cjk)
    for name, files in (("orientations.html", books), ("orientations-cjk.html", zh)):
        run = subprocess.run([meridian, "gyro", "orientations", *files, "-q", "--report", os.path.join(out, name)],
                             capture_output=True, text=True)
        if run.returncode != 0:
            return f"meridian gyro orientations --report {name}: " + run.stderr
    return None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--meridian", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--examples", required=True)
    ap.add_argument("--screenshots", action="store_true")
    args = ap.parse_args()
    chromium = find_chromium()
    if not chromium:
        print("FAIL: no chromium on PATH; install Debian's chromium (scripts/setup.sh does)")
        return 1
    shutil.rmtree(args.out, ignore_errors=True)
    demo = subprocess.run([args.meridian, "demo", "--output-dir", args.out], capture_output=True, text=True)
    if demo.returncode != 0:
        print("FAIL: meridian demo:", demo.stderr)
        return 1
    passed = failed = 0
    for problem in (write_gravity_report(args.meridian, args.out), write_dov_report(args.meridian, args.out),
                    write_cjk_campaign_report(args.meridian, args.examples, args.out),
                    write_orientations_reports(args.meridian, args.out)):
        if problem:
            failed += 1
            print("FAIL", problem)
    pages = sorted(glob.glob(os.path.join(args.out, "*.html")))
    for page in pages:
        errs = check_page(chromium, page)
        if errs:
            failed += 1
            print(f"FAIL {page}")
            for e in errs:
                print("   ", e)
        else:
            passed += 1
            print(f"ok   {page}")
    # Every page must be one the check knows, so new reports get section checks.
    for name in REQUIRED:
        if not os.path.exists(os.path.join(args.out, name)):
            # A real-data job the demo skips on a fresh clone (its logs live in ../shared/data,
            # never in the project): absent only when the demo said it skipped that job.
            job = REAL_DATA_JOBS.get(name)
            if job and re.search(re.escape(job) + r" skipped: .* is not there", demo.stdout):
                print(f"skip {name}: the demo skipped {job} (its real logs are not on this machine)")
                continue
            failed += 1
            print(f"FAIL {name} was not written")
    # The campaign report prints to a PDF.
    pdf = os.path.join(args.out, "campaign.pdf")
    p = subprocess.run([args.meridian, "report", "pdf", os.path.join(args.out, "campaign.html"), "-o", pdf],
                       capture_output=True, text=True)
    data = open(pdf, "rb").read() if os.path.exists(pdf) else b""
    pages_in_pdf = len(re.findall(rb"/Type\s*/Page[^s]", data))
    if p.returncode != 0 or not data.startswith(b"%PDF") or pages_in_pdf < 2:
        failed += 1
        print(f"FAIL meridian report pdf (exit {p.returncode}, {pages_in_pdf} pages): {p.stderr}")
    else:
        passed += 1
        print(f"ok   {pdf} ({pages_in_pdf} A4 pages)")
    # Chinese names print with a CJK font (fonts-noto-cjk), not as empty boxes.
    pdf = os.path.join(args.out, "campaign-cjk.pdf")
    p = subprocess.run([args.meridian, "report", "pdf", os.path.join(args.out, "campaign-cjk.html"), "-o", pdf],
                       capture_output=True, text=True)
    data = open(pdf, "rb").read() if os.path.exists(pdf) else b""
    if p.returncode != 0 or b"NotoSansCJK" not in data:
        failed += 1
        print(f"FAIL {pdf}: no Noto CJK font embedded for the Chinese names (exit {p.returncode}) {p.stderr}")
    else:
        passed += 1
        print(f"ok   {pdf} (Chinese names set in Noto Sans CJK)")
    # The result sheet in each language: its labels, and a picture of it kept beside the page.
    sheets = {"campaign.html": ["Result sheet", "Grid azimuth", "gyro minus traverse azimuth", "Known line", "Runs"],
              "campaign-cjk.html": ["陀螺定向成果表", "坐标方位角 Grid azimuth", "仪器常数 E", "一次测定中误差",
                                    "陀螺方位角与导线方位角之差", "已知边 Known line", "观测者"],
              "orientations.html": ["Result sheet of the independent orientations", "Mean grid azimuth",
                                    "shared parts (correlated)", "as if independent (not used)", "Orientations",
                                    "mean minus traverse azimuth", "computed by"],
              "orientations-cjk.html": ["陀螺定向成果表", "平均坐标方位角 Mean grid azimuth", "平均值中误差",
                                        "共同部分 (相关)", "各次定向 Orientations", "各次定向共同的误差来源",
                                        "计算者", "张工"]}
    for name, labels in sheets.items():
        page = os.path.join(args.out, name)
        if not os.path.exists(page):
            continue
        html = open(page, encoding="utf-8").read()
        end = html.find('id="inputs"') if 'id="inputs"' in html else html.find('id="checks"')
        sheet = html[html.find('id="result-sheet"'):end]
        missing = [l for l in labels if l not in sheet]
        # The campaign's computation sheet (计算表) and checks after the result sheet, in the job's language.
        if name == "campaign-cjk.html":
            missing += [l for l in ("计算表 Computation sheet", "限差检核 Tolerance checks", "拉普拉斯改正")
                        if l not in html]
        png = page[:-5] + ".png"
        shot = subprocess.run([args.meridian, "report", "screenshot", page, "-o", png], capture_output=True, text=True)
        if missing or shot.returncode != 0 or not os.path.exists(png) or os.path.getsize(png) < 10000:
            failed += 1
            print(f"FAIL {name} result sheet: missing {missing}, screenshot exit {shot.returncode} {shot.stderr}")
        else:
            passed += 1
            print(f"ok   {name} result sheet ({len(labels)} labels; picture {png})")
    if args.screenshots:
        for page in pages:
            subprocess.run([args.meridian, "report", "screenshot", page], check=False)
    print(f"{passed} passed, {failed} failed")
    return 0 if failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
