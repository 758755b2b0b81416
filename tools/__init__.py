"""Build tools of the course, run from the repository root as modules.

``python -m tools.build_slides [DEST]`` lecture decks (the sources through sphinx-revealjs)
``python -m tools.slides_pdf [DEST]``   PDF handouts of the decks (headless Chromium)
``python -m tools.to_ipynb DEST``       the notebooks as .ipynb, for nbval
``python -m tools.vendor``              front-end files from node_modules
``python -m tools.cache_guard``         empty the book's cache after a library change
``python -m tools.make_exercises DEST`` student notebooks
``python -m tools.bench``               speed benchmark

Which files are notebooks and which get a deck is decided in one place,
``_ext/notebook_pages.py``, shared with the book's Sphinx extensions.
"""
