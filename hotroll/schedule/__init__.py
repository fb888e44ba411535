"""Pass schedules (issue 17): a strip rolled pass after pass, with interpass transports.

``config.py`` the schedule file, ``run.py`` the passes and transports, ``plots.py`` the
figure; ``hotroll schedule FILE --out DIR`` on the command line.
"""
