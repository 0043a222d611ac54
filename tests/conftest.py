import os
import sys
import tempfile
from pathlib import Path

# Servers started by tests keep their default episode store in a fresh directory,
# never in the user's data directory.
os.environ["XDG_DATA_HOME"] = tempfile.mkdtemp(prefix="verigraph-test-data-")
# Never let a test reach for a model hub.
os.environ.setdefault("HF_HUB_OFFLINE", "1")
sys.path.insert(0, str(Path(__file__).parent))
