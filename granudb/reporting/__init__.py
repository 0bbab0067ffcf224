"""Lab reports in HTML and Markdown: the values, verdicts, fits and figures of a pair or a
dataset, rendered from the records the analysis layer computed (its words included), with
the figures drawn as SVG and the page checked in headless Chromium by the tests.
"""
