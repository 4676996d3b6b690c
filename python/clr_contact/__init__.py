"""The former name of the contact-law part of :mod:`clr` (``clr_sim.contact``), kept so that code
written for it runs unchanged: ``import clr_contact as cc`` gives the same laws, plus
``run_model``/``list_models`` and the errors of :mod:`clr`."""

from clr_sim.contact import *  # noqa: F401,F403
from clr_sim.contact import __all__ as _contact_all
from clr_sim.contact import __version__  # noqa: F401
from clr_sim.errors import ModelError, SimulationError  # noqa: F401
from clr_sim import list_models, run_model  # noqa: F401

__all__ = list(_contact_all) + ["ModelError", "SimulationError", "list_models", "run_model"]
