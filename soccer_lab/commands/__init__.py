"""The argparse front-ends of ``soccer-env train``, ``eval`` and ``ablation``.

Each module has ``parser()`` (the options and their help) and ``main(argv)`` (parse, check,
run the library function of :mod:`agents`, print). :mod:`soccer_lab.cli` imports a command's
module when the command runs: training needs the ``train`` extra.
"""
