#!/usr/bin/env bash
# The evaluation (issue 10): builds (through tools/setup.sh), runs the designed scenarios and the
# city-like run through criticality-campaign (ours with SUMO's SSM device, the closed loop, the
# ablations the driver offers) and writes eval/ (tables, figures, index.html).
# Usage: tools/evaluate.sh [--out DIR] [--full] [--only a,b] [-j N] ...   (--help: every option)
# Without --full the city-like run covers its first 120 s; tools/evaluate/README.md says more.
set -euo pipefail
cd "$(dirname "$0")/.."
# Debian's Python has Debian's matplotlib (python3-matplotlib, installed by setup.sh); another
# python3 first on PATH (pyenv, a venv) may not. CRIT_PYTHON overrides.
python=${CRIT_PYTHON:-}
if [ -z "$python" ]; then
  python=python3
  [ -x /usr/bin/python3 ] && python=/usr/bin/python3
fi
case " $* " in
  *" -h "*|*" --help "*) exec "$python" tools/evaluate/evaluate.py --help ;;
esac
if [ -z "${EVALUATE_NO_BUILD:-}" ]; then
  echo "evaluate: building (the first run installs packages and compiles for a few minutes)" >&2
  ./tools/setup.sh >&2
fi
exec "$python" tools/evaluate/evaluate.py "$@"
