#!/usr/bin/env python3
"""binpickd's web view in a real headless browser.

Starts binpickd replaying the virtual cell's test bin with the web view on a free port, opens the
page in headless Chromium (Selenium), runs a cycle over the robot protocol (ASCII framing, a plain
socket) and waits for the new cycle's picks and overlay to appear on the page without a reload.
Exits 77 (skipped) when Selenium, Chromium or chromedriver is missing.

    browser_test.py --binpickd PATH --scene PATH [--screenshot PNG] [--cycles N] [--keep-open S]
"""
import argparse
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

SKIP = 77


def find_browser():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


def wait_for(what, predicate, timeout):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(0.05)
    raise TimeoutError("timed out waiting for " + what)


class Robot:
    """A robot controller on the ASCII framing: one request, one reply line."""

    def __init__(self, port):
        self.sock = socket.create_connection(("127.0.0.1", port), timeout=120)
        self.buffer = b""

    def ask(self, request):
        self.sock.sendall(request.encode() + b"\r\n")
        while b"\n" not in self.buffer:
            chunk = self.sock.recv(4096)
            if not chunk:
                raise ConnectionError("binpickd closed the robot connection")
            self.buffer += chunk
        line, self.buffer = self.buffer.split(b"\n", 1)
        return line.decode().strip().split(",")

    def close(self):
        self.sock.close()


def start_daemon(binpickd, config, directory):
    port_file = os.path.join(directory, "port")
    log_path = os.path.join(directory, "stderr")
    log = open(log_path, "w")
    daemon = subprocess.Popen([binpickd, "--config", config, "--port", "0", "--port-file", port_file],
                              stderr=log, stdout=subprocess.DEVNULL)

    def ports():
        if daemon.poll() is not None:
            raise RuntimeError("binpickd exited: " + open(log_path).read())
        if not os.path.exists(port_file):
            return None
        web = re.search(r"web view on (http://[0-9.]+:[0-9]+/)", open(log_path).read())
        return (int(open(port_file).read()), web.group(1)) if web else None

    robot_port, url = wait_for("binpickd to listen", ports, 180)
    return daemon, robot_port, url


def run_cycle(robot):
    trigger = robot.ask("TRIGGER")
    assert trigger[:2] == ["TRIGGER", "0"], trigger
    first = robot.ask("NEXT")
    assert first[:2] == ["NEXT", "0"], first
    return int(trigger[2])


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--binpickd", required=True)
    parser.add_argument("--scene", required=True, help="writes the settings for the test bin")
    parser.add_argument("--screenshot", help="save a screenshot of the page after the last cycle")
    parser.add_argument("--cycles", type=int, default=1)
    args = parser.parse_args()

    try:
        from selenium import webdriver
        from selenium.webdriver.chrome.service import Service
        from selenium.webdriver.common.by import By
        from selenium.webdriver.support.ui import WebDriverWait
    except ImportError:
        print("SKIP: python3-selenium is not installed")
        return SKIP
    browser, driver_path = find_browser(), shutil.which("chromedriver")
    if not browser or not driver_path:
        print("SKIP: chromium or chromedriver is not installed")
        return SKIP

    directory = tempfile.mkdtemp(prefix="binpick_web_browser_")
    daemon = driver = robot = None
    try:
        config = subprocess.run([args.scene, directory], check=True, capture_output=True, text=True).stdout.strip()
        daemon, robot_port, url = start_daemon(args.binpickd, config, directory)

        options = webdriver.ChromeOptions()
        options.binary_location = browser
        for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                     "--window-size=1440,1320", "--hide-scrollbars"):
            options.add_argument(flag)
        driver = webdriver.Chrome(service=Service(driver_path), options=options)
        driver.get(url)
        wait = WebDriverWait(driver, 60, poll_frequency=0.1)
        wait.until(lambda d: d.find_element(By.ID, "state").get_attribute("data-state") == "idle")
        assert driver.find_elements(By.CSS_SELECTOR, "#picks tbody tr.pick") == []
        # Set on this page only: a reload would lose it.
        driver.execute_script("window.sameDocument = 'yes';")

        robot = Robot(robot_port)
        for _ in range(args.cycles):
            cycle = run_cycle(robot)
            # The picks, then the overlay, of the new cycle appear without a reload.
            wait.until(lambda d: d.find_element(By.CSS_SELECTOR, "#picks tbody").get_attribute("data-cycle") == str(cycle))
            rows = driver.find_elements(By.CSS_SELECTOR, "#picks tbody tr.pick")
            assert rows, "no pick rows for cycle %d" % cycle
            assert rows[0].find_elements(By.TAG_NAME, "td")[0].text == "1"
            wait.until(lambda d: d.execute_script(
                "const img = document.getElementById('overlay');"
                "return !img.hidden && img.complete && img.naturalWidth > 0 && img.dataset.cycle === arguments[0];",
                str(cycle)))
        wait.until(lambda d: d.find_element(By.ID, "state").get_attribute("data-state") == "waiting_for_robot")
        assert driver.find_element(By.ID, "cycle").text == str(cycle)
        assert "l_bracket" in driver.find_element(By.ID, "recipe").text
        assert driver.find_elements(By.CSS_SELECTOR, "#robots tbody tr"), "the robot is listed"
        wait.until(lambda d: d.find_elements(By.CSS_SELECTOR, "#chart rect"))
        assert driver.execute_script("return window.sameDocument;") == "yes", "the page was reloaded"
        # The low-coverage count of this cycle's reply, and of an earlier binpickd's (named
        # not_sure there), shown the same way.
        for key in ("low_coverage", "not_sure"):
            shown = driver.execute_async_script(
                "const [key, done] = arguments;"
                "fetch('/api/status', {cache: 'no-store'}).then((r) => r.json()).then((status) => {"
                "  const counts = status.last_cycle.counts;"
                "  delete counts.low_coverage;"
                "  counts[key] = 3;"
                "  showRejected(status);"
                "  done(document.getElementById('rejected').textContent);"
                "});", key)
            assert "3 coverage below the minimum" in shown, (key, shown)
        if args.screenshot:
            time.sleep(1.5)  # one more poll: the log and the chart settle
            driver.save_screenshot(args.screenshot)
        print("the page showed cycle %d's %d picks and its overlay without a reload" % (cycle, len(rows)))
        return 0
    finally:
        if robot:
            robot.close()
        if driver:
            driver.quit()
        if daemon and daemon.poll() is None:
            daemon.send_signal(signal.SIGTERM)
            try:
                daemon.wait(60)
            except subprocess.TimeoutExpired:
                daemon.kill()
        shutil.rmtree(directory, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
