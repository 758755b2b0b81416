"""Lecture slides from the chapter sources: MyST-to-reveal conversion and templates.

``reader``      reads MyST Markdown with myst-parser: directive blocks, the
                pieces of a cell, headings, the labels a source defines;
``myst``        turns MyST Markdown (directives, roles, labels) into the plain
                Markdown + HTML that nbconvert renders, with styled boxes;
``preprocess``  the nbconvert preprocessor that applies it to a notebook and
                decides what each cell shows on a slide;
``templates/``  the nbconvert template ``course`` (reveal.js and MathJax 3, no CDN).
"""
