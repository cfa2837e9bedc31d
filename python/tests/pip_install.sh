#!/usr/bin/env bash
# Installs the package exactly as the README says (a venv over Debian's python3 and its packages, then
# `pip install --no-build-isolation .` from the checkout, offline), then runs the README's example with it.
# Usage: pip_install.sh CHECKOUT. The CMake build goes to a temporary folder unless TM_BUILD_DIR is set.
set -euo pipefail
checkout=$(cd "$1" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export TM_BUILD_DIR=${TM_BUILD_DIR:-$work/build}
/usr/bin/python3 -m venv --system-site-packages "$work/venv"
cd "$checkout"
"$work/venv/bin/pip" install --no-build-isolation --no-index --quiet .
# The README's example, taken from the README itself, run outside the checkout (the installed package, not python/).
/usr/bin/python3 - "$checkout/README.md" "$work/example.py" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
section = text[text.index("## Python"):]
open(sys.argv[2], "w").write(re.search(r"```python\n(.*?)```", section, re.S).group(1))
PY
cd "$work"
"$work/venv/bin/python" example.py | tee "$work/out.txt"
grep -q " tets" "$work/out.txt"
grep -q "potential .* V" "$work/out.txt"
