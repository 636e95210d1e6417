"""Suite-wide settings: hypothesis runs the same examples on every run.

The ``ci`` profile (the default) derandomises hypothesis (the examples follow from each test's
source, not from a random seed), keeps no example database between runs (a failure found once is
not replayed forever after, and a clean checkout behaves like any other) and sets no deadline (a
2-core machine under load times single examples unevenly). ``--hypothesis-profile=thorough``
draws ten times as many random examples for a long, opt-in run.
"""

from hypothesis import HealthCheck, settings

settings.register_profile(
    "ci",
    derandomize=True,
    database=None,
    deadline=None,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile(
    "thorough",
    derandomize=False,
    database=None,
    deadline=None,
    max_examples=1000,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile("ci")
