import sys

from verigraph.cli import main

sys.exit(main())
