"""`clothref view` pages in headless Chromium (ctest browser_view; tools/clothref/cmd_view.cpp,
tools/pages/assets/viewer.js).

Usage: view_page_test.py --cli build/bin/clothref --screenshots DIR

Checks, on a one-trace page and on a pair whose first difference is known (a copy of the trace
with one particle moved from step 1500 on): the viewer mounted, no console message, no network
request, the canvas is not blank, moving the slider and the next button change the picture, play
advances, the marker and the text name step 1500, the cloth is coloured by distance at step 1500
and not before, side by side differs from overlaid, the page opens in under 2 s. Screenshots of
each page go to --screenshots.
"""
import gzip
import json
import os
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import browser  # noqa: E402

FIRST = 1500  # the step the pair first differs at


def run(cli, *args):
    result = subprocess.run([cli, *args], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f'clothref {" ".join(args)} failed ({result.returncode}): {result.stderr}')
    return result.stderr


def moved_copy(source, target, from_step, particle, dy):
    """`target`: the trace `source` with cloth particle `particle` moved by dy (m) from a step on."""
    with gzip.open(source, 'rt') as lines, open(target, 'w') as out:
        # The edited steps keep their old hashes: a header that does not describe the state hash
        # tells the reader not to check them (an unchanged description would make them corrupt).
        header = json.loads(next(lines))
        header['hash'] = 'edited by the browser test: hashes of the original run, not recomputed'
        out.write(json.dumps(header, separators=(',', ':')) + '\n')
        for line in lines:
            step = json.loads(line)
            if step['step'] >= from_step:
                step['bodies']['cloth']['position'][particle][1] += dy
                line = json.dumps(step, separators=(',', ':')) + '\n'
            out.write(line)


def yellow_pixels(image):
    """Pixels of the top colour of the distance scale (viridis yellow, shaded): red and green
    alike and well above blue; not the reference's blue-purple, the spheres or the orange wire."""
    return sum(1 for r, g, b in image.getdata()
               if g > 80 and abs(r - g) < 0.25 * max(r, g) and b < 0.5 * g)


def set_frame(b, frame):
    b.js("const s = arguments[0].querySelector('.cv-slider'); s.value = arguments[1];"
         "s.dispatchEvent(new Event('input'));", b.driver.find_element('css selector', '#viewer'),
         frame)


def open_page(b, checks, path, name):
    started = time.monotonic()
    url = b.open(path)
    opened = time.monotonic() - started
    ready = b.js("return document.getElementById('viewer').dataset.ready === '1'")
    checks.check(ready, f'{name}: the viewer mounted')
    timing = b.js("const n = performance.getEntriesByType('navigation')[0];"
                  "return n ? n.loadEventEnd : -1")
    mount = b.js("return document.getElementById('viewer').dataset.loadMs")
    print(f'      {name}: {os.path.getsize(path) / 1e6:.2f} MB, load event at {timing:.0f} ms, '
          f'mount {mount} ms, driver.get {opened:.2f} s')
    checks.check(0 < timing < 2000, f'{name}: opens in under 2 s (load event at {timing:.0f} ms)')
    return url


def main():
    options, checks = browser.start()
    with tempfile.TemporaryDirectory(prefix='clothref-view-test-') as tmp:
        one = os.path.join(tmp, 'one.jsonl.gz')
        run(options.cli, 'trace', '-q', '--steps', '3000', '--stride', '10', '-o', one)
        pair = os.path.join(tmp, 'moved.jsonl')
        moved_copy(one, pair, FIRST, 20 * 25 + 16, 0.05)  # in front of the spheres
        one_html, pair_html = os.path.join(tmp, 'one.html'), os.path.join(tmp, 'pair.html')
        run(options.cli, 'view', one, '--max-frames', '120', '-o', one_html)
        summary = run(options.cli, 'view', one, pair, '--labels', 'reference', 'moved',
                      '--max-frames', '120', '-o', pair_html)
        checks.check(f'first difference at step {FIRST}' in summary, f'view names step {FIRST}')
        b = browser.Browser()
        try:
            # ---- one trace
            url = open_page(b, checks, one_html, 'one trace')
            canvas0 = b.element_image('.cv-canvas')
            checks.check(browser.non_background_fraction(canvas0) > 0.05,
                         'one trace: the canvas is not blank '
                         f'({browser.non_background_fraction(canvas0):.1%} drawn)')
            note = b.js("return document.querySelector('.cv-decimation').textContent")
            checks.check('Showing 120 of 301 recorded steps' in note, f'decimation stated: {note}')
            set_frame(b, 119)
            canvas1 = b.element_image('.cv-canvas')
            moved = browser.changed_fraction(canvas0, canvas1)
            checks.check(moved > 0.02, f'moving the slider changes the picture ({moved:.1%})')
            label = b.js("return document.querySelector('.cv-time').textContent")
            checks.check(label.startswith('step 3000 of 3000'), f'time label at the end: {label}')
            b.save_screenshot(os.path.join(options.screenshots, 'view-one.png'))
            set_frame(b, 40)
            before = b.element_image('.cv-canvas')
            b.driver.find_element('css selector', '.cv-next').click()
            after = b.element_image('.cv-canvas')
            checks.check(b.js("return document.getElementById('viewer').dataset.frame") == '41'
                         and browser.changed_fraction(before, after) > 0.001,
                         'the next button steps one frame and the picture changes')
            b.driver.find_element('css selector', '.cv-play').click()
            time.sleep(0.6)
            frame = int(b.js("return document.getElementById('viewer').dataset.frame"))
            checks.check(frame > 42, f'play advances (frame {frame} after 0.6 s)')
            browser.check_quiet(b, checks, url, 'one trace')

            # ---- the pair
            url = open_page(b, checks, pair_html, 'pair')
            marker = b.js("const m = document.querySelector('.cv-marker');"
                          "return m ? [m.dataset.step, m.style.left] : null")
            frame_steps = b.js("return JSON.parse(document.getElementById('viewer-data')"
                               ".textContent).frame_steps")
            checks.check(marker is not None and marker[0] == str(FIRST),
                         f'the slider marks step {FIRST} ({marker})')
            if marker and FIRST in frame_steps:
                k = frame_steps.index(FIRST)
                expected = 100 * k / (len(frame_steps) - 1)
                checks.check(abs(float(marker[1].rstrip('%')) - expected) < 1e-6,
                             f'the marker sits at frame {k} ({marker[1]})')
                first_text = b.js("return document.querySelector('.cv-first').textContent")
                checks.check(f'First difference at step {FIRST}' in first_text, first_text)
                set_frame(b, k - 1)
                same = b.element_image('.cv-canvas')
                set_frame(b, k)
                differ = b.element_image('.cv-canvas')
                checks.check(yellow_pixels(same) == 0 and yellow_pixels(differ) > 20,
                             f'distance colouring: {yellow_pixels(same)} yellow pixels before '
                             f'step {FIRST}, {yellow_pixels(differ)} at it')
                b.save_screenshot(os.path.join(options.screenshots, 'view-pair-overlay.png'))
                b.js("const s = document.querySelector('.cv-layout'); s.value = 'side';"
                     "s.dispatchEvent(new Event('change'));")
                side = b.element_image('.cv-canvas')
                checks.check(browser.changed_fraction(differ, side) > 0.05,
                             'side by side differs from overlaid')
                b.save_screenshot(os.path.join(options.screenshots, 'view-pair-side.png'))
            else:
                checks.check(False, f'step {FIRST} is among the frames {frame_steps}')
            plot = b.element_image('.cv-plot')
            checks.check(browser.non_background_fraction(plot) > 0.01,
                         'the difference plot is drawn')
            browser.check_quiet(b, checks, url, 'pair')
        finally:
            b.close()
    checks.finish()


if __name__ == '__main__':
    main()
