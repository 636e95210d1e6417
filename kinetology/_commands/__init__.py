"""The subcommands of the ``kinetology`` command, a module per group: each adds its parsers
(``register(sub)``) and holds the handlers that do the work.

:mod:`kinetology.cli` assembles them into the command (and into ``psgs kinetology``). Below
the groups stand what several share: :mod:`.options` (the motion file, frame rate,
segmentation and codec options, with their help texts) and :mod:`.files` (reading a take for
a command, writing its output). A group imports numpy and the modules that do the work in its
handlers, when they run, so that making the parser (every ``--help`` and ``--version``) does
not load them.
"""
