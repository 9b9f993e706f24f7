#!/usr/bin/env python3
"""Writes the Gradescope autograder archive (behind `clothref gradescope`):

  setup.sh, run_autograder     at the zip root (from this folder), executable
  rubric.json                  the rubric, when --rubric is given
  clothref/                    the sources of the checkout's HEAD commit (git archive: no build
                               folder, no .git), plus REVISION (the commit, for --version) and
                               gradescope.env (edition, probe timeout, HTML report)

Usage: make_archive.py -o autograder.zip [--edition 2022|2024] [--rubric FILE] [--html]
                       [--timeout S] [--source DIR]
Bad input: one line on stderr, exit 2, no archive written (written to a temporary file, renamed).
"""
import argparse
import io
import json
import os
import subprocess
import sys
import tarfile
import tempfile
import time
import zipfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
SOURCE = HERE.parents[2]
ROOT_FILES = ("setup.sh", "run_autograder")


class BadInput(Exception):
    pass


def git(source, *args, binary=False):
    run = subprocess.run(["git", "-C", str(source), *args], capture_output=True, check=False)
    if run.returncode != 0:
        message = run.stderr.decode("utf-8", "replace").strip().splitlines()
        raise BadInput(f"{source}: git {args[0]} failed: {message[0] if message else run.returncode}")
    return run.stdout if binary else run.stdout.decode().strip()


def add(archive, name, data, executable=False, mtime=None):
    info = zipfile.ZipInfo(name, date_time=time.gmtime(mtime or 315532800)[:6])
    info.compress_type = zipfile.ZIP_DEFLATED
    info.external_attr = ((0o100755 if executable else 0o100644) & 0xFFFF) << 16
    archive.writestr(info, data)


def read_rubric(path):
    path = Path(path)
    if not path.is_file():
        raise BadInput(f"--rubric: {path}: not a regular file")
    data = path.read_bytes()
    try:
        json.loads(data)
    except (ValueError, UnicodeDecodeError) as error:
        raise BadInput(f"--rubric: {path}: not JSON ({error})") from None
    return data


def settings(options):
    return (f"# Written by `clothref gradescope`: read by run_autograder.\n"
            f"EDITION={options.edition or ''}\n"
            f"TIMEOUT={options.timeout if options.timeout is not None else ''}\n"
            f"HTML={1 if options.html else 0}\n")


def write_archive(options):
    source = Path(options.source).resolve()
    commit = git(source, "rev-parse", "HEAD")
    revision = git(source, "describe", "--always", "--abbrev=12")
    if git(source, "status", "--porcelain", "--untracked-files=no"):
        print(f"clothref gradescope: uncommitted changes in {source} are not in the archive "
              f"(it holds commit {revision})", file=sys.stderr)
    rubric = read_rubric(options.rubric) if options.rubric else None
    sources = tarfile.open(fileobj=io.BytesIO(git(source, "archive", "--format=tar", commit,
                                                  binary=True)))
    output = Path(options.output)
    if output.is_dir():
        raise BadInput(f"-o: {output}: is a directory")
    folder = output.parent if str(output.parent) else Path(".")
    if not folder.is_dir():
        raise BadInput(f"-o: {output}: folder {folder} does not exist")
    handle, temporary = tempfile.mkstemp(prefix=output.name + ".", suffix=".tmp", dir=folder)
    try:
        with os.fdopen(handle, "wb") as raw, zipfile.ZipFile(raw, "w") as archive:
            for name in ROOT_FILES:
                add(archive, name, (HERE / name).read_bytes(), executable=True)
            if rubric is not None:
                add(archive, "rubric.json", rubric)
            for member in sources:
                if member.isfile():
                    add(archive, "clothref/" + member.name, sources.extractfile(member).read(),
                        executable=bool(member.mode & 0o111), mtime=member.mtime)
            add(archive, "clothref/REVISION", revision + "\n")
            add(archive, "clothref/gradescope.env", settings(options))
        os.replace(temporary, output)
    except BaseException:
        os.unlink(temporary)
        raise
    return commit


def main():
    parser = argparse.ArgumentParser(prog="clothref gradescope", description=__doc__.split("\n")[0])
    parser.add_argument("-o", "--output", required=True, help="the archive to write (.zip)")
    parser.add_argument("--edition", choices=["2022", "2024"], help="force the edition")
    parser.add_argument("--rubric", help="rubric JSON for clothref grade --rubric")
    parser.add_argument("--html", action="store_true", help="also write report.html")
    parser.add_argument("--timeout", type=float, help="wall-clock limit per probe (s)")
    parser.add_argument("--source", default=str(SOURCE), help="the clothref checkout")
    options = parser.parse_args()
    try:
        if options.timeout is not None and not (0 < options.timeout <= 86400):
            raise BadInput(f"--timeout: must be a number of seconds in (0, 86400] "
                           f"(got {options.timeout})")
        commit = write_archive(options)
    except (BadInput, OSError) as error:
        print(f"clothref gradescope: {error}", file=sys.stderr)
        return 2
    size = Path(options.output).stat().st_size
    print(f"wrote {options.output}: {size} bytes, clothref {commit[:12]}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
