#!/usr/bin/env python3
"""The held-out protocol's networks are made by Debian's SUMO as network_family.py says: one
network of each set is generated (netgenerate, randomTrips with duarouter), its configuration
loads and runs in SUMO, and a second generation reuses the folder unchanged. Needs sumo,
netgenerate and sumo-tools (tools/setup.sh installs them)."""

import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "tools", "evaluate"))

import network_family  # noqa: E402


class GenerateTest(unittest.TestCase):
    def test_one_network_of_each_set_is_made_and_runs_in_sumo(self):
        with tempfile.TemporaryDirectory() as root:
            for net in (network_family.Network("grid", 1, 1.0),
                        network_family.Network("rand", 3, 0.1)):
                cfg = network_family.generate(net, root)
                self.assertTrue(cfg.endswith(f"{net.name}.sumocfg"))
                folder = os.path.dirname(cfg)
                routes = open(os.path.join(folder, "cars.rou.xml"), encoding="utf-8").read()
                self.assertGreater(routes.count("<vehicle "), 10)
                self.assertIn('vClass="bicycle"',
                              open(os.path.join(folder, "bikes.rou.xml"), encoding="utf-8").read())
                self.assertGreater(open(os.path.join(folder, "peds.rou.xml"),
                                        encoding="utf-8").read().count("<person "), 10)
                env = dict(os.environ, SUMO_HOME=os.environ.get("SUMO_HOME", "/usr/share/sumo"))
                p = subprocess.run(["sumo", "-c", cfg, "--end", "30", "--no-step-log", "true"],
                                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                   env=env)
                self.assertEqual(p.returncode, 0, p.stdout[-2000:])
                # Made once: a second call keeps the folder (the network file is not rewritten).
                stamp = os.path.getmtime(os.path.join(folder, f"{net.net_name}.net.xml"))
                network_family.generate(net, root)
                self.assertEqual(stamp, os.path.getmtime(
                    os.path.join(folder, f"{net.net_name}.net.xml")))


if __name__ == "__main__":
    unittest.main()
