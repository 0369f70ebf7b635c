"""The errors of nmm's tools as Python exceptions.

The tools exit with status 2 on bad input, printing one line "FILE: WHERE: WHAT"; the module
raises InputError with that line as its text (str(e)) and its parts as attributes. SceneError
is the InputError of a scene: a scene file or dict, its --set variants, a point or polyline of
it the solver cannot place; `where` is then the JSON path (/joints/3/points/1, /solver/time_step).
RunError is the tools' exit status 3 (a run that cannot go on), raised by nmm.solve(check=True).
"""


class InputError(ValueError):
    """Bad input (the tools' exit status 2): str(e) is their one line "FILE: WHERE: WHAT"."""

    def __init__(self, line, file="", where="", message=""):
        super().__init__(line)
        self.file = file        # the file at fault ("" for the command line's --set)
        self.where = where      # a JSON path such as /joints/3/points/1, "line L, column C", "byte N"
        self.message = message  # what is wrong


class SceneError(InputError):
    """A scene that cannot be used, at the JSON path `where`."""


class RunError(RuntimeError):
    """A run that could not go on (the tools' exit status 3): `outcome` says why, `run` holds
    what it wrote (nmm.Run)."""

    def __init__(self, reason, outcome=None, run=None):
        super().__init__(reason)
        self.outcome = outcome
        self.run = run


class SceneWarning(UserWarning):
    """What nmm-preprocess warns of: legal, but likely a mistake (a joint touching no body, a
    mesh size above a body's inradius, a mesh that takes minutes to cut)."""
