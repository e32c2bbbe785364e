"""The studio: a local web page where a person types Japanese, watches it act and exports it.

``text2anim studio`` (:mod:`cli.cmd_studio`) serves :func:`app.create_app` on 127.0.0.1 with
uvicorn; :mod:`work` turns a text into what the page shows (the viewer page of
:mod:`output.viewer` and the time table), :mod:`guard` keeps other web pages and hosts out.
"""
