"""`python -m pytest_lasertest.cli`: the `lasertest` command without its script."""

from __future__ import annotations

import sys

from pytest_lasertest.cli import main

sys.exit(main())
