"""Copies the browser tests' screenshots into docs/pictures/ for docs/pictures.md, reduced to 256
colours (the pages are flat colours; this keeps each file small in the repository).

Usage (after `ctest --test-dir build -L browser`):
    /usr/bin/python3 tests/browser/docs_screenshots.py build/screenshots docs/pictures
"""
import os
import sys

from PIL import Image

NAMES = ['view-pair-overlay.png', 'view-pair-side.png', 'report.png', 'report-stub.png',
         'report-sketch.png', 'report-whole-run.png', 'class-index.png', 'class-index-1280.png',
         'class-index-1920.png', 'gradescope-results.png', 'gradescope-picture.png']


def main(source, target):
    os.makedirs(target, exist_ok=True)
    for name in NAMES:
        image = Image.open(os.path.join(source, name)).convert('RGB')
        image.quantize(colors=256, method=Image.Quantize.MEDIANCUT).save(
            os.path.join(target, name), optimize=True)
        print(f'{name}: {os.path.getsize(os.path.join(target, name)) / 1e3:.0f} kB')


if __name__ == '__main__':
    main(*sys.argv[1:3])
