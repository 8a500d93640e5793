"""CTest python_example: runs the walkthrough examples/python/dzhanibekov.py
headless (Matplotlib's Agg) into a fresh folder and checks that every figure
it announces exists and is a non-empty PNG.
Usage: check_example.py EXAMPLE OUT_DIR"""
import os
import shutil
import subprocess
import sys

example, out_dir = sys.argv[1], sys.argv[2]
shutil.rmtree(out_dir, ignore_errors=True)
r = subprocess.run([sys.executable, example, "--out-dir", out_dir], capture_output=True, text=True,
                   env=dict(os.environ, MPLBACKEND="Agg"))
sys.stdout.write(r.stdout)
sys.stderr.write(r.stderr)
if r.returncode != 0:
    sys.exit(f"check_example: {example} exited with {r.returncode}")
expected = ["book_flip.png", "book_error_vs_cpu.png", "heavy_top.png"]
for name in expected:
    path = os.path.join(out_dir, name)
    if not os.path.isfile(path) or os.path.getsize(path) == 0:
        sys.exit(f"check_example: {path} was not written")
    with open(path, "rb") as f:
        if f.read(8) != b"\x89PNG\r\n\x1a\n":
            sys.exit(f"check_example: {path} is not a PNG")
    if path not in r.stdout:
        sys.exit(f"check_example: the example did not say it wrote {path}")
print(f"check_example: {len(expected)} figures in {out_dir}")
