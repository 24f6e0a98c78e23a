# The plugin's own tests: pytester runs inner pytest sessions with the plugin enabled.
pytest_plugins = ["pytester"]
