#!/usr/bin/python3
"""Runs Jupyter notebooks top to bottom and fails on the first cell that raises (notebooks are tests).

    run_notebooks.py [--timeout S] [--build DIR] [--save DIR] NOTEBOOK.ipynb...

Each notebook runs in a kernel of this interpreter (Debian's /usr/bin/python3, where
python3-ipykernel, NumPy and matplotlib live), whatever kernels the user has installed: the
runner writes its own kernel spec into a temporary folder and puts that first on JUPYTER_PATH. The
kernel finds the module through PYTHONPATH (ctest sets it; otherwise <build>/python is added). The
working directory is the notebook's folder. With --save the executed notebooks, outputs included,
are written to DIR (the sources are never changed).
"""
import argparse
import json
import os
import sys
import tempfile
import time
from pathlib import Path

import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError

ROOT = Path(__file__).resolve().parent.parent
KERNEL = "fremond-python3"


def kernel_spec_dir(tmp: Path) -> Path:
    """A kernels/<name>/kernel.json running ipykernel under this very interpreter."""
    spec = tmp / "kernels" / KERNEL
    spec.mkdir(parents=True)
    (spec / "kernel.json").write_text(json.dumps({
        "argv": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"],
        "display_name": f"Python 3 ({sys.executable})",
        "language": "python",
    }))
    return tmp


def run(path: Path, timeout: int, save: Path | None) -> bool:
    nb = nbformat.read(path, as_version=4)
    client = NotebookClient(nb, timeout=timeout, kernel_name=KERNEL,
                            resources={"metadata": {"path": str(path.parent)}})
    started = time.time()
    try:
        client.execute()
        ok = True
    except CellExecutionError as e:
        print(f"{path.name}: a cell failed:\n{e}", file=sys.stderr)
        ok = False
    finally:
        if save is not None:
            save.mkdir(parents=True, exist_ok=True)
            nbformat.write(nb, save / path.name)
    print(f"{path.name}: {'ok' if ok else 'FAILED'} in {time.time() - started:.1f} s")
    return ok


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("notebooks", nargs="+", type=Path)
    ap.add_argument("--timeout", type=int, default=120, help="seconds per cell (default 120)")
    ap.add_argument("--build", type=Path, default=ROOT / "build",
                    help="build folder holding python/fremond, when PYTHONPATH is not set")
    ap.add_argument("--save", type=Path, help="write the executed notebooks to this folder")
    args = ap.parse_args(argv)

    if not os.environ.get("PYTHONPATH"):
        os.environ["PYTHONPATH"] = str((args.build / "python").resolve())
    os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # quiet debugger start-up
    os.environ.pop("MPLBACKEND", None)  # the kernel's own inline backend: figures become outputs
    with tempfile.TemporaryDirectory(prefix="fremond-kernel-") as tmp:
        jupyter_path = [str(kernel_spec_dir(Path(tmp)))]
        if os.environ.get("JUPYTER_PATH"):
            jupyter_path.append(os.environ["JUPYTER_PATH"])
        os.environ["JUPYTER_PATH"] = os.pathsep.join(jupyter_path)
        results = [run(p.resolve(), args.timeout, args.save) for p in args.notebooks]
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main())
