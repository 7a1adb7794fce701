"""Fixtures of the explorer's browser test: the built page served by `polbrdf explore`, headless
Chromium driven by Selenium (the system's chromium and chromedriver), and the release CLI whose
numbers the page must show.

Environment: POLBRDF_CLI (default target/release/polbrdf), POLBRDF_WEB_DIST (default
web/dist), POLBRDF_WEB_OUT (screenshots and timings; default target/web-test), CHROMIUM and
CHROMEDRIVER (default /usr/bin/chromium and /usr/bin/chromedriver).
"""

from __future__ import annotations

import os
import subprocess
import time
from pathlib import Path

import pytest
from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.support.ui import WebDriverWait

ROOT = Path(__file__).resolve().parents[2]


def _path(var: str, default: Path) -> Path:
    return Path(os.environ.get(var, str(default))).resolve()


@pytest.fixture(scope="session")
def cli() -> Path:
    path = _path("POLBRDF_CLI", ROOT / "target" / "release" / "polbrdf")
    assert path.is_file(), f"{path}: build it with `cargo build --release -p polbrdf-cli`"
    return path


@pytest.fixture(scope="session")
def out_dir() -> Path:
    d = _path("POLBRDF_WEB_OUT", ROOT / "target" / "web-test")
    d.mkdir(parents=True, exist_ok=True)
    return d


@pytest.fixture(scope="session")
def server(cli: Path):
    """`polbrdf explore` on a free port; yields the page's URL."""
    dist = _path("POLBRDF_WEB_DIST", ROOT / "web" / "dist")
    proc = subprocess.Popen(
        [str(cli), "explore", "--dir", str(dist), "--port", "0"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )
    # The address is a note for a person: standard error (docs/cli-conventions.md, Streams).
    line = proc.stderr.readline() if proc.stderr else ""
    if not line.startswith("polbrdf explorer: http://"):
        proc.kill()
        _, err = proc.communicate()
        pytest.fail(f"polbrdf explore did not start: {line!r} {err}")
    yield line.split(": ", 1)[1].strip()
    proc.terminate()
    proc.wait(timeout=10)


@pytest.fixture(scope="session")
def driver(out_dir: Path):
    opts = webdriver.ChromeOptions()
    opts.binary_location = os.environ.get("CHROMIUM", "/usr/bin/chromium")
    for arg in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage",
                "--window-size=1500,1900", "--force-device-scale-factor=1"):
        opts.add_argument(arg)
    service = Service(os.environ.get("CHROMEDRIVER", "/usr/bin/chromedriver"))
    d = webdriver.Chrome(options=opts, service=service)
    # A scene's recompute (sky integrals and emission over a band) may hold the page for tens
    # of seconds on a loaded machine.
    d.set_script_timeout(900)
    d.execute_cdp_cmd(
        "Page.setDownloadBehavior", {"behavior": "allow", "downloadPath": str(out_dir)}
    )
    yield d
    d.quit()


@pytest.fixture()
def page(driver, server):
    """Opens the page (state from `hash`, URL-encoded) and waits until it has computed."""

    def open_page(hash_: str = "") -> webdriver.Chrome:
        driver.get("about:blank")
        driver.get(f"{server}#{hash_}")
        WebDriverWait(driver, 60).until(
            lambda d: d.execute_script("return document.body.dataset.ready === 'true'")
            or d.find_element("id", "status").text.startswith("failed")
        )
        status = driver.find_element("id", "status").text
        assert status.startswith("polbrdf"), status
        return driver

    return open_page


def wait_computed(driver, before: int) -> None:
    """Waits until the page has recomputed after a control changed."""
    WebDriverWait(driver, 60).until(
        lambda d: int(d.execute_script("return document.body.dataset.computed || 0")) > before
    )
    time.sleep(0.05)
