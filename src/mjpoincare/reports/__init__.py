"""Report commands: they run validations and measurements through the public layers and write generated pages."""
