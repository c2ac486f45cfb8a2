"""Command-line interface (``roughcontact``)."""
