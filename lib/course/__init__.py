"""Course content: what the book teaches with the library (chapter set-up, exercise definitions).

The machinery that runs it lives in ``jacobians`` (the numeric core and its teaching layer).
"""
