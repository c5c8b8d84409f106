#!/usr/bin/env bash
# CI: Debian's chromium for the end-to-end app test (tests/test_app_browser.py), installed with apt-get when it is
# missing.  The playwright Python package comes with the test extra (pip install ".[test]"); it drives this system
# chromium (executable_path=/usr/bin/chromium); `playwright install` (which downloads browsers) is never run.
set -euo pipefail
if [[ ! -x /usr/bin/chromium ]]; then
    SUDO=""
    if [[ "$(id -u)" != 0 ]] && command -v sudo >/dev/null; then SUDO="sudo"; fi
    $SUDO apt-get update
    $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends chromium
fi
/usr/bin/chromium --version || true
