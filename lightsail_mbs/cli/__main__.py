import sys

from lightsail_mbs.cli import main

sys.exit(main())
