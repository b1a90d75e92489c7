"""``python -m mjpoincare``: the command line (:func:`mjpoincare.cli.main`)."""

import sys

from mjpoincare.cli import main

sys.exit(main())
