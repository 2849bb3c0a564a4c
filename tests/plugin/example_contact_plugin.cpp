// placeholder (being replaced)
