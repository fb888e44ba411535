"""Everything that holds NGSolve objects: meshes, spaces, the weak forms, the traced top
boundary, strain and temperature fields, and the figures measured on them. Imports: model,
config, theory, examples, files."""
