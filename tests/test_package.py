"""Package-level contract: light import, public names."""

import subprocess
import sys

import pytest

import jacobians as jac


def test_import_loads_numpy_only():
    code = ("import sys, jacobians; heavy = [m for m in ('sympy', 'matplotlib', 'ipywidgets', 'scipy', 'pinocchio') "
            "if m in sys.modules]; print(','.join(heavy))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""


@pytest.mark.parametrize(("module", "expected"), [
    ("jacobians.symbolic", "sympy"),
    ("jacobians.plotting", "matplotlib"),
    ("jacobians.widgets", "matplotlib,ipywidgets"),
    ("jacobians.grading", ""),
])
def test_subpackages_import_what_the_package_docstring_says(module, expected):
    code = (f"import sys, {module}; heavy = [m for m in ('sympy', 'matplotlib', 'ipywidgets') "
            "if m in sys.modules]; print(','.join(heavy))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == expected


def test_grading_imports_sympy_only_for_a_symbolic_answer():
    code = ("import sys, numpy as np; from jacobians import grading; "
            "ex = grading.numeric_exercise('t', 's', {}, np.eye(2), []); "
            "ok = ex.check(np.eye(2)).correct; print(ok, 'sympy' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "True False"


def test_public_api_names():
    for name in ["SerialChain", "space_jacobian", "body_jacobian", "geometric_jacobian", "analytic_jacobian",
                 "pose_coordinates", "space_to_body", "body_to_space", "body_to_geometric", "geometric_to_body",
                 "adjoint", "robots", "jacobian", "Frame", "FRAMES", "frames"]:
        assert hasattr(jac, name), name
    for name in ["planar_2r", "planar_3r", "ur5"]:
        assert callable(getattr(jac.robots, name))
