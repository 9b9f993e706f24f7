"""Headless Chromium for the page tests (ctest label `browser`), driven by chromedriver through
python3-selenium (Debian packages chromium, chromium-driver, python3-selenium; tools/setup.sh).

A test exits 77 (ctest SKIP_RETURN_CODE) with one line saying what is missing only when Chromium,
chromedriver or selenium is genuinely absent; anything else that goes wrong is a failure.
"""
import argparse
import io
import json
import os
import shutil
import sys
import tempfile

SKIP = 77
CHROMIUM = '/usr/bin/chromium'
CHROMEDRIVER = '/usr/bin/chromedriver'


def skip_unless_available():
    missing = [p for p in (CHROMIUM, CHROMEDRIVER) if not os.access(p, os.X_OK)]
    try:
        import markdown  # noqa: F401
        import selenium  # noqa: F401
        from PIL import Image  # noqa: F401
    except ImportError as error:
        missing.append(f'python module {error.name}')
    if missing:
        print(f'SKIP: {", ".join(missing)} not installed (tools/setup.sh installs chromium, '
              'chromium-driver, python3-selenium, python3-pil, python3-markdown)')
        sys.exit(SKIP)


def start(*extra_options):
    """A test's start: its options (--cli, --screenshots and `extra_options`, all required), the
    skip when the browser is absent, and an empty Checks."""
    parser = argparse.ArgumentParser()
    for option in ('--cli', '--screenshots', *extra_options):
        parser.add_argument(option, required=True)
    options = parser.parse_args()
    skip_unless_available()
    return options, Checks()


class Checks:
    """Collects failed checks, so one run reports all of them."""

    def __init__(self):
        self.failed = []

    def check(self, condition, what):
        print(('ok    ' if condition else 'FAIL  ') + what)
        if not condition:
            self.failed.append(what)

    def finish(self):
        if self.failed:
            print(f'{len(self.failed)} check(s) failed')
            sys.exit(1)
        print('all checks passed')


class Browser:
    """One headless Chromium with a fresh profile in a temporary directory (removed on close)."""

    def __init__(self, width=1200, height=1000):
        from selenium import webdriver
        from selenium.webdriver.chrome.service import Service
        self.profile = tempfile.mkdtemp(prefix='clothref-browser-')
        options = webdriver.ChromeOptions()
        options.binary_location = CHROMIUM
        for flag in ('--headless', '--no-sandbox', '--disable-gpu', '--disable-quic',
                     '--no-first-run', '--disable-background-networking',
                     '--disable-component-update', '--disable-sync', '--hide-scrollbars',
                     '--force-device-scale-factor=1', f'--window-size={width},{height}',
                     f'--user-data-dir={self.profile}'):
            options.add_argument(flag)
        options.set_capability('goog:loggingPrefs', {'browser': 'ALL', 'performance': 'ALL'})
        self.driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
        self.driver.set_page_load_timeout(60)

    def close(self):
        try:
            self.driver.quit()
        finally:
            shutil.rmtree(self.profile, ignore_errors=True)

    def open(self, path):
        """Loads a local file; returns the page's URL."""
        url = 'file://' + os.path.abspath(path)
        self.driver.get(url)
        return url

    def console_problems(self):
        """Console messages of level WARNING or worse since the last call."""
        return [e for e in self.driver.get_log('browser') if e['level'] in ('SEVERE', 'WARNING')]

    def requests(self, page_url):
        """Since the last call: URLs the page asked for (other than itself and data: URLs), and
        any request to the network from anywhere (the browser's own chrome:// pages aside)."""
        urls = []
        for entry in self.driver.get_log('performance'):
            message = json.loads(entry['message'])['message']
            if message.get('method') != 'Network.requestWillBeSent':
                continue
            url = message['params']['request']['url']
            from_page = message['params'].get('documentURL') == page_url
            if (from_page and url != page_url and not url.startswith('data:')) or \
                    url.split(':', 1)[0] in ('http', 'https', 'ws', 'wss', 'ftp'):
                urls.append(url)
        return urls

    def js(self, script, *args):
        return self.driver.execute_script(script, *args)

    def element_image(self, css):
        """The element's pixels as a PIL RGB image (a screenshot of it)."""
        from PIL import Image
        from selenium.webdriver.common.by import By
        png = self.driver.find_element(By.CSS_SELECTOR, css).screenshot_as_png
        return Image.open(io.BytesIO(png)).convert('RGB')

    def save_screenshot(self, path):
        os.makedirs(os.path.dirname(path), exist_ok=True)
        self.driver.save_screenshot(path)


def check_quiet(b, checks, page_url, name):
    """No console message and no network request since the last look (the page's own file and
    data: URLs aside)."""
    problems = b.console_problems()
    checks.check(not problems, f'{name}: no console messages {problems}')
    requests = b.requests(page_url)
    checks.check(not requests, f'{name}: no network request {requests}')


def changed_fraction(a, b):
    """Fraction of pixels that differ between two same-sized images."""
    if a.size != b.size:
        return 1.0
    pa, pb = a.getdata(), b.getdata()
    return sum(1 for x, y in zip(pa, pb) if x != y) / max(1, len(pa))


def non_background_fraction(image):
    """Fraction of pixels that are not the image's most common colour (its background)."""
    colours = image.getcolors(maxcolors=1 << 24)
    background = max(colours)[0]
    return 1 - background / (image.size[0] * image.size[1])
