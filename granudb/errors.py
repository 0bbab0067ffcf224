"""The one exception type granudb raises for anything a user can fix.

Every refusal names the field, the value and the rule, so the command line can print it
as one line (``Error: density: -3 kg/m^3 must be > 0``) with no traceback.
"""

from __future__ import annotations


class GranudbError(ValueError):
    """A refusal a user can act on; ``str()`` is the whole one-line message."""

    exit_code = 1


class ValidationError(GranudbError):
    """A value from outside (CLI option, CSV cell, package field) breaks a rule."""

    def __init__(
        self,
        field: str,
        value: object,
        rule: str,
        *,
        row: int | None = None,
        parameter: bool = False,
    ) -> None:
        if field.startswith("--") and field[2:].replace("-", "").isalnum():
            # Named as the command line spells it (``--output``): kept as the Python
            # parameter (``output``), so each caller reads the name it used.
            field, parameter = field[2:].replace("-", "_"), True
        self.field = field
        self.value = value
        self.rule = rule
        self.row = row
        #: ``field`` is a parameter of the Python API (``temperature``); the command line
        #: names the same input ``--temperature`` (one name, two spellings).
        self.parameter = parameter
        super().__init__(self.render(field))

    def render(self, field: str) -> str:
        """The one-line message with ``field`` as the caller names it."""
        where = f"row {self.row}: " if self.row is not None else ""
        # A value with a newline or other control character is shown escaped, so the
        # message stays one line whatever the input.
        value = self.value
        shown = value if isinstance(value, str) and value.isprintable() else repr(value)
        return f"{where}{field}: {shown} {self.rule}"

    def as_option(self) -> str:
        """The message for the command line: a Python parameter becomes its option."""
        if self.parameter:
            return self.render("--" + self.field.replace("_", "-"))
        return str(self)


class MissingInput(ValidationError):
    """A required value was not given (``None``); the command line says it as a missing
    option, with the command's usage."""

    def __init__(self, field: str, rule: str = "is required") -> None:
        super().__init__(field, "(missing)", rule, parameter=True)


class NotFoundError(GranudbError):
    """A named thing (material, fluid, source, dataset) is not in the database."""


class ConflictError(GranudbError):
    """The request would break uniqueness or a reference (duplicate name, row in use)."""


class SchemaError(GranudbError):
    """The database is at a schema revision this granudb cannot work with."""


class DatabaseAccessError(GranudbError):
    """The database cannot be opened or written (missing directory, read-only, full)."""


class ConfirmationNeeded(GranudbError):
    """A destructive change was asked for without the person's consent (``--yes`` or a
    "y" at the prompt); nothing was changed."""


class PackageError(GranudbError):
    """A Data Package fails validation; ``problems`` lists every problem found."""

    def __init__(self, problems: list[str], hint: str = "") -> None:
        self.problems = problems
        first = problems[0] if problems else "unknown problem"
        more = f" (and {len(problems) - 1} more{hint})" if len(problems) > 1 else ""
        super().__init__(f"package: {first}{more}; nothing was imported")
