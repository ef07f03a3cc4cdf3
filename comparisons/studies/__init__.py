"""The studies, one package (or module) each, in the report's order
(:data:`.registry.STUDIES`)."""
