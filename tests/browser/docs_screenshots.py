"""Copies the browser tests' screenshots into docs/pictures/ for docs/pictures.md, reduced to 256
colours (the pages are flat colours; this keeps each file small in the repository).

Usage (after `ctest --test-dir build -L browser`):
    /usr/bin/python3 tests/browser/docs_screenshots.py build/screenshots docs/pictures
"""
import os
import sys

from PIL import Image

NAMES = ['view-pair-overlay.png', 'view-pair-side.png', 'report.png', 'report-sketch.png',
         'report-whole-run.png', 'class-index.png', 'gradescope-results.png',
         'gradescope-picture.png']
# class-index-1280.png and class-index-1920.png in docs/pictures are of the corpus batch (80
# submissions), taken by hand as docs/pictures.md says; the test's own are of its fixture.


def main(source, target):
    os.makedirs(target, exist_ok=True)
    for name in NAMES:
        image = Image.open(os.path.join(source, name)).convert('RGB')
        image.quantize(colors=256, method=Image.Quantize.MEDIANCUT).save(
            os.path.join(target, name), optimize=True)
        print(f'{name}: {os.path.getsize(os.path.join(target, name)) / 1e3:.0f} kB')


if __name__ == '__main__':
    main(*sys.argv[1:3])
