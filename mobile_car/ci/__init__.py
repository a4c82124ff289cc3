"""``mcar ci`` as a library: build, check and render a whole package; JUnit reports."""
