"""The model-agnostic stability engine: eigen-analysis of ẋ = A(V) x along the airspeed."""
from propwhirl.engine.core import *  # noqa: F401,F403
from propwhirl.engine.core import __all__  # noqa: F401
