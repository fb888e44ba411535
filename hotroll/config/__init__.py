"""The input language: pydantic schemas of a case, a pass schedule and a study, each field
with its unit and allowed range. Imports: model, theory, examples, files."""
