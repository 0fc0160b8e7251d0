"""``python -m station``: the same CLI as the ``station`` command (also under ``torchrun -m station``)."""

from station.cli import main

raise SystemExit(main())
