"""What a sumo-criticality binary offers, read from its --help: the long option names and
their defaults. The evaluation runs a variant only when the driver has every option it needs."""

import re
import subprocess

# "  --warn-threshold arg (=0.5)    p_cra that ..." or "  -c [ --sumo-config ] arg    ..."
_OPTION = re.compile(r"^  (?:-\w \[ )?--([A-Za-z0-9][\w.-]*)(?: \])?(?: arg)?(?: \(=([^)]*)\))?")


class DriverHelp:
    def __init__(self, text):
        self.text = text
        self.options = {}  # name -> default text (None when none is shown)
        for line in text.splitlines():
            m = _OPTION.match(line)
            if m:
                self.options[m.group(1)] = m.group(2)

    def has(self, name):
        return name in self.options

    def default_float(self, name, fallback):
        """The numeric default of an option, else fallback (no default shown, or not a number:
        e.g. '0.8 x warn threshold')."""
        try:
            return float(self.options.get(name))
        except (TypeError, ValueError):
            return fallback


def read_driver_help(driver):
    """DriverHelp of the binary; RuntimeError with a one-line reason when it cannot be run."""
    try:
        proc = subprocess.run([driver, "--help"], capture_output=True, text=True, timeout=60)
    except OSError as e:
        raise RuntimeError(f"cannot run {driver}: {e.strerror} (build it: tools/setup.sh)") from None
    if proc.returncode != 0:
        raise RuntimeError(f"{driver} --help exited {proc.returncode}: {proc.stderr.strip()[:200]}")
    return DriverHelp(proc.stdout)
