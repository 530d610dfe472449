"""Every public name of the package mo2d has a docstring beyond its signature (as docs.api checks
the C++ headers): the module's functions, its classes, and their public methods and properties.
help(mo2d.forward_dynamics) must say what the call does, not only how it is spelled."""
import inspect
import re

import mo2d

# A line pybind11 writes itself: a signature "name(arg: type, ...) -> type" (numbered "1. " in an
# overloaded function's list; without the name for a property's getter), "name(*args, **kwargs)"
# or the "Overloaded function." heading.
SIGNATURE = re.compile(r"^\s*(\d+\.\s+)?([A-Za-z_][A-Za-z_0-9]*)?"
                       r"\((.*\)\s*->\s*\S.*|\*args, \*\*kwargs\))\s*$")


def explanation(doc):
    """The docstring's text without pybind11's signature lines (empty: signature only)."""
    lines = [line for line in (doc or "").splitlines()
             if not SIGNATURE.match(line) and line.strip() != "Overloaded function."]
    return " ".join(" ".join(lines).split())


def documented(doc):
    return len(explanation(doc).split()) >= 3  # a sentence, not "the t"


def public_names():
    """(qualified name, docstring) of every public name: mo2d.__all__, the public attributes of
    each class (methods, properties, static methods) and the constructors of the classes."""
    for name in sorted(mo2d.__all__):
        obj = getattr(mo2d, name)
        if inspect.isclass(obj):
            yield f"mo2d.{name}", obj.__doc__
            for attr, value in sorted(vars(obj).items()):
                if attr.startswith("_") and attr != "__init__":
                    continue
                if attr == "__init__" and obj.__module__ == "builtins":
                    continue
                qualified = f"mo2d.{name}.{attr}"
                if isinstance(value, property):
                    yield qualified, value.__doc__ or (value.fget and value.fget.__doc__)
                elif isinstance(value, (staticmethod, classmethod)):
                    yield qualified, value.__func__.__doc__
                elif callable(value) or inspect.isdatadescriptor(value):
                    yield qualified, getattr(value, "__doc__", None)
        elif callable(obj):
            yield f"mo2d.{name}", obj.__doc__


def test_the_walk_finds_the_api():
    names = dict(public_names())
    # the module functions, the classes and their members are all walked
    for name in ("mo2d.forward_dynamics", "mo2d.System", "mo2d.System.add_body",
                 "mo2d.Result.columns", "mo2d.Scene.duration", "mo2d.load_scene"):
        assert name in names, name
    assert len(names) > 150


def test_signature_only_docstrings_are_recognized():
    assert not documented("forward_dynamics(model: Model, t1: float) -> Result\n")
    assert not documented(None)
    assert not documented("(self: mo2d._mo2d.Result) -> list[str]\n")
    assert not documented("f(*args, **kwargs)\nOverloaded function.\n\n1. f(x: int) -> int\n\n"
                          "2. f(x: str) -> int\n")
    assert documented("f(x: int) -> int\n\nThe number of links of x.\n")
    assert documented("y(x) at points, a cubic spline (S, S', S'')")


def test_every_public_name_has_a_docstring():
    missing = [name for name, doc in public_names() if not documented(doc)]
    assert not missing, (f"{len(missing)} public names without a docstring beyond the "
                         "signature:\n  " + "\n  ".join(missing))
