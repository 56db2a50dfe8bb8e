"""The argparse front-ends of ``soccer-env train``, ``eval``, ``ablation`` and ``play``.

Each command has ``parser()`` (the options and their help) and ``main(argv)`` (parse, check,
run the library function of :mod:`agents`, print). :mod:`soccer_lab.cli` imports a command's
module when the command runs: training needs the ``train`` extra, playing the ``render``
extra. The options of ``train`` are declared once in :mod:`soccer_lab.commands.train_options`;
``play`` is a package (keys, games, window, loop).
"""
