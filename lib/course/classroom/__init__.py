"""Grading a class: collect the students' notebooks, run each in a sandbox, regrade, write a gradebook.

Modules: :mod:`~course.classroom.answer_data` (an answer as JSON data and back,
never through ``eval``), :mod:`~course.classroom.sandbox` (a notebook or a
student's function run as an unprivileged process with limits),
:mod:`~course.classroom.grade` (``make grade``: find, run, regrade, gradebook,
reports), :mod:`~course.classroom.report` (the HTML report of one student).

This package imports nothing at import time, so the kernel of a notebook under
``make grade`` can use :mod:`~course.classroom.answer_data` cheaply.
"""
