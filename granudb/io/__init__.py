"""Getting data in and out: units at the edges, CSV and seed files, validation."""
